// A build without threads (src/threads.cpp compiled with CHAINDRIVE_NO_THREADS, as a source FMU
// for a target without std::thread is): one thread runs, more are refused by name.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "threads.h"

using chaindrive::StagePool;

TEST(ThreadsAbsent, OneRunsMoreAreRefusedByName) {
  EXPECT_FALSE(chaindrive::threadsAvailable());
  StagePool one(1);
  int ran = 0;
  auto task = [&](int t) { ran += t + 1; };
  one.run(task);
  EXPECT_EQ(ran, 1);
  try {
    StagePool two(2);
    FAIL() << "two threads in a build without threads";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "solver.threads = 2: this build has no threads (a source build without std::thread); allowed: 1");
  }
}
