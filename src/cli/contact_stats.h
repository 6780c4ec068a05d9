// The counters of a rigid-contact method in a tool's JSON summary (chaindrive-run, chaindrive-cvt).
#pragma once

#include <nlohmann/json.hpp>

#include "nonsmooth/system.h"

namespace chaindrive::cli {

inline void addContactStats(const ns::NsStats& cs, nlohmann::json& j) {
  j["events"] = cs.events;
  j["impacts"] = cs.impacts;
  j["lcpSolves"] = cs.lcpSolves;
  j["lcpSizeMean"] = cs.lcpSolves ? static_cast<double>(cs.lcpSizeSum) / static_cast<double>(cs.lcpSolves) : 0.0;
  j["lcpSizeMax"] = cs.lcpSizeMax;
  j["pivots"] = cs.pivots;
  j["regularizedLcps"] = cs.regularizedLcps;
  j["contactSteps"] = cs.steps;
}

}  // namespace chaindrive::cli
