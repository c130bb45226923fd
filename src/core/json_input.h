#pragma once
// JSON files the user writes (transfer functions, illustration styles): parsed with
// nlohmann::json, every failure an InputError of one line naming the file, and small readers
// for the values such files hold, each naming where in the file the value sits
// ("tf.json: point 3: opacity: must be a number in [0, 1]"); and the text of the JSON it writes.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace vsil {

// Parses `text`; InputError "<source>: not valid JSON (line L, column C: what)" otherwise.
nlohmann::json parseJsonText(std::string_view text, const std::string& source);

// Reads the whole file (at most limits::kMaxHeaderBytes) and parses it.
nlohmann::json readJsonFile(const std::string& path);
// The same, keeping the file's order of keys (where the order means something: sweep axes).
nlohmann::ordered_json readOrderedJsonFile(const std::string& path);

// The text of JSON vsil writes (--json, --meta-out, info --json, the serve API, ...), indented
// as nlohmann's dump(indent). Bytes that are not UTF-8, which a Linux file name may hold and
// JSON may not, become U+FFFD instead of an exception after the work is done.
std::string jsonText(const nlohmann::json& value, int indent = -1);

// A short, printable rendering of a JSON value for messages (at most ~40 characters).
std::string jsonSnippet(const nlohmann::json& value);

// A finite number; InputError "<where>: must be a number (got ...)" otherwise.
double jsonNumber(const nlohmann::json& value, const std::string& where);
// A string; InputError "<where>: must be a string (got ...)" otherwise.
const std::string& jsonString(const nlohmann::json& value, const std::string& where);
// Every key of `object` is one of `known`; InputError "<where>: unknown key 'k' (known: ...)".
void checkJsonKeys(const nlohmann::json& object, const std::vector<std::string>& known,
                   const std::string& where);

}  // namespace vsil
