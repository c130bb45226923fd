#pragma once
// Parsing numbers and words out of text headers (NRRD, legacy VTK, VTI attributes). Every
// failure is an InputError "<where>: <field> ...", never a std::stoi-style exception.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace vsil::io {

std::string_view trim(std::string_view text);
std::string toLower(std::string_view text);
std::vector<std::string_view> splitWhitespace(std::string_view text);

// The whole token must be a number in range; `field` names it in the message.
std::int64_t parseInteger(const std::string& where, const std::string& field,
                          std::string_view token);
double parseReal(const std::string& where, const std::string& field, std::string_view token);

// Exactly three positive integers (sizes, DIMENSIONS), each within int.
glm::ivec3 parseDims(const std::string& where, const std::string& field, std::string_view text);
// Exactly three finite, positive reals (spacings).
glm::dvec3 parseSpacing(const std::string& where, const std::string& field, std::string_view text);
// Throws unless every component is finite and positive.
void checkSpacing(const std::string& where, const std::string& field, glm::dvec3 spacing);

// The path of the detached data file that the header file `header` names (NRRD `data file`,
// MetaImage ElementDataFile), a relative name from the header's folder. Throws InputError
// "`header`: `label`: ..." for a name holding a NUL byte, which no file name can (opened, it
// would name the file its first part names).
std::string dataFilePath(const std::string& header, const std::string& label,
                         const std::string& name);

// Shortens text quoted in an error message and replaces control bytes, so a message stays on
// one line whatever the file held.
std::string quote(std::string_view text);

}  // namespace vsil::io
