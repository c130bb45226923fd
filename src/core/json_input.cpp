#include "core/json_input.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/limits.h"
#include "io/file_access.h"
#include "io/text_fields.h"

namespace vsil {

namespace {

// nlohmann's messages name the position and what went wrong after a fixed prefix; control
// characters of the input come escaped (<U+000A>), but a long token may be quoted whole.
std::string conciseReason(const std::string& what) {
  std::string reason = what;
  const std::string marker = "parse error at ";
  if (const auto at = reason.find(marker); at != std::string::npos) {
    reason = reason.substr(at + marker.size());
  } else if (const auto bracket = reason.find("] "); bracket != std::string::npos) {
    reason = reason.substr(bracket + 2);
  }
  std::replace_if(
      reason.begin(), reason.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  constexpr std::size_t kMaxReason = 160;
  if (reason.size() > kMaxReason) reason = reason.substr(0, kMaxReason) + "...";
  return reason;
}

}  // namespace

namespace {

// parseJsonText for either JSON type (nlohmann::ordered_json keeps the file's key order).
template <typename Json>
Json parseGuarded(std::string_view text, const std::string& source) {
  // The parser itself keeps its nesting on the heap, but every later walk of the value
  // (dump, comparison, the readers) recurses: a file of 100000 '[' would overflow the stack
  // there. The callback sees each container open with the count of those enclosing it.
  // A key given twice in one object is refused too: nlohmann keeps the last one silently (as
  // duplicate header fields are refused in the volume formats).
  struct TooDeep {};
  struct DuplicateKey {
    std::string key;
  };
  std::vector<std::set<std::string>> objectKeys;  // of each object being parsed
  const auto guard = [&objectKeys](int depth, typename Json::parse_event_t event, Json& parsed) {
    using Event = typename Json::parse_event_t;
    if ((event == Event::object_start || event == Event::array_start) &&
        depth >= limits::kMaxJsonDepth) {
      throw TooDeep{};
    }
    if (event == Event::object_start) objectKeys.emplace_back();
    if (event == Event::object_end) objectKeys.pop_back();
    if (event == Event::key &&
        !objectKeys.back().insert(parsed.template get<std::string>()).second) {
      throw DuplicateKey{parsed.template get<std::string>()};
    }
    return true;
  };
  try {
    return Json::parse(text.begin(), text.end(), guard);
  } catch (const TooDeep&) {
    throwInputError(source, "not valid JSON (nested more than " +
                                std::to_string(limits::kMaxJsonDepth) + " levels deep)");
  } catch (const DuplicateKey& e) {
    throwInputError(source, "the key " + io::quote(e.key) +
                                " is given twice in one object (which one counts?)");
  } catch (const typename Json::exception& e) {
    throwInputError(source, "not valid JSON (" + conciseReason(e.what()) + ")");
  }
}

}  // namespace

nlohmann::json parseJsonText(std::string_view text, const std::string& source) {
  return parseGuarded<nlohmann::json>(text, source);
}

nlohmann::json readJsonFile(const std::string& path) {
  return parseJsonText(io::readWholeFile(path, limits::kMaxHeaderBytes), path);
}

nlohmann::ordered_json readOrderedJsonFile(const std::string& path) {
  return parseGuarded<nlohmann::ordered_json>(io::readWholeFile(path, limits::kMaxHeaderBytes),
                                              path);
}

std::string jsonText(const nlohmann::json& value, int indent) {
  return value.dump(indent, ' ', /*ensure_ascii=*/false, nlohmann::json::error_handler_t::replace);
}

namespace {

// Appends `value` as compact JSON until `text` holds more than `budget` characters: a message
// quotes the start of a value, so a large or deep one is never serialised whole (each level
// adds a character, so the recursion stops within `budget` levels).
void appendSnippet(const nlohmann::json& value, std::string& text, std::size_t budget) {
  if (text.size() > budget) return;
  const auto dumpScalar = [](const nlohmann::json& scalar) {
    return scalar.dump(-1, ' ', /*ensure_ascii=*/true, nlohmann::json::error_handler_t::replace);
  };
  if (value.is_object()) {
    text += '{';
    bool first = true;
    for (const auto& item : value.items()) {
      if (text.size() > budget) return;
      if (!first) text += ',';
      first = false;
      const std::string& key = item.key();
      text += dumpScalar(nlohmann::json(key.substr(0, budget + 1))) + ':';
      appendSnippet(item.value(), text, budget);
    }
    text += '}';
  } else if (value.is_array()) {
    text += '[';
    bool first = true;
    for (const auto& item : value) {
      if (text.size() > budget) return;
      if (!first) text += ',';
      first = false;
      appendSnippet(item, text, budget);
    }
    text += ']';
  } else if (value.is_string()) {
    // Only the start of a long string is escaped and quoted.
    text += dumpScalar(nlohmann::json(value.get_ref<const std::string&>().substr(0, budget + 1)));
  } else {
    text += dumpScalar(value);
  }
}

}  // namespace

std::string jsonSnippet(const nlohmann::json& value) {
  constexpr std::size_t kMax = 40;
  std::string text;
  appendSnippet(value, text, kMax);
  if (text.size() > kMax) text = text.substr(0, kMax) + "...";
  return text;
}

double jsonNumber(const nlohmann::json& value, const std::string& where) {
  if (!value.is_number())
    throwInputError(where, "must be a number (got " + jsonSnippet(value) + ")");
  const double number = value.get<double>();
  if (!std::isfinite(number)) throwInputError(where, "must be a finite number");
  return number;
}

const std::string& jsonString(const nlohmann::json& value, const std::string& where) {
  if (!value.is_string())
    throwInputError(where, "must be a string (got " + jsonSnippet(value) + ")");
  return value.get_ref<const std::string&>();
}

void checkJsonKeys(const nlohmann::json& object, const std::vector<std::string>& known,
                   const std::string& where) {
  for (const auto& item : object.items()) {
    if (std::find(known.begin(), known.end(), item.key()) != known.end()) continue;
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    throwInputError(where, "unknown key " + jsonSnippet(item.key()) + " (known: " + list + ")");
  }
}

}  // namespace vsil
