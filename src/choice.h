// A choice (integrator method, contact method, joint model, contact law, fidelity, rotation) is an enum
// below the boundary. Its names are one table, ChoiceNames<E>::table, declared beside the enum.
// The boundary (the description reader, the command-line tools, the FMUs) turns a name into the
// enum once, with choiceOf or parseChoice, and reports an unknown name in one format
// (unknownChoiceText) that lists the allowed names; below it, code compares enums, not strings.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace chaindrive {

template <class E>
struct ChoiceName {
  E value;
  const char* name;
};

/// Specialized beside each choice's enum with `static constexpr ChoiceName<E> table[] = {...};`.
template <class E>
struct ChoiceNames;

/// The value of a name; nullopt for a name not in the table.
template <class E>
std::optional<E> choiceOf(std::string_view name) {
  for (const auto& c : ChoiceNames<E>::table)
    if (name == c.name) return c.value;
  return std::nullopt;
}

/// The name of a value (for messages, summaries and files).
template <class E>
const char* choiceName(E value) {
  for (const auto& c : ChoiceNames<E>::table)
    if (c.value == value) return c.name;
  return "?";
}

template <class E>
std::vector<std::string> choiceNames() {
  std::vector<std::string> names;
  for (const auto& c : ChoiceNames<E>::table) names.emplace_back(c.name);
  return names;
}

/// "a, b, c".
inline std::string listOfNames(const std::vector<std::string>& names) {
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  return list;
}

/// The one message of a name that is not among the allowed ones: "'x' is unknown; allowed: a, b".
inline std::string unknownChoiceText(std::string_view given, const std::vector<std::string>& allowed) {
  return "'" + std::string(given) + "' is unknown; allowed: " + listOfNames(allowed);
}

/// The value of a name; throws std::invalid_argument "<what>: 'x' is unknown; allowed: ...".
template <class E>
E parseChoice(std::string_view name, const std::string& what) {
  if (auto value = choiceOf<E>(name)) return *value;
  throw std::invalid_argument(what + ": " + unknownChoiceText(name, choiceNames<E>()));
}

}  // namespace chaindrive
