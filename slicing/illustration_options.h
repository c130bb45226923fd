#pragma once
// The options that carry an illustration (src/core/illustration.h) into a technique: declared
// once here (any technique that applies the paper's formulas declares the same flags) and
// resolved here from an OptionReader into what a frame uses.
#include <string>
#include <vector>

#include "core/illustration.h"
#include "core/options.h"

namespace vsil {

// The #define shaders/illustration.glsl needs: "LIGHT_COUNT n", n the illustration's lights.
std::string lightCountDefine(const Illustration& illustration);

// --param NAME=VALUE,... (repeatable). `allowed` limits the names (empty: every parameter);
// `owner` names the technique in the message for others.
OptionSpec parameterOption(std::vector<std::string> allowed = {}, std::string owner = "");
// --light AZ,EL (repeatable).
OptionSpec lightOption();
// --effects LIST, --style NAME|FILE, --tf FILE, --color C, --sketch-color C.
OptionSpec effectsOption();
OptionSpec styleOption();
OptionSpec transferFunctionOption();
OptionSpec colorOption();
OptionSpec sketchColorOption();

// What the options given set (files read here: --style, --tf). Options a technique does not
// declare are left alone.
IllustrationStyle styleFromOptions(const std::vector<OptionSpec>& declared,
                                   const OptionReader& options);
// The style (--style, else `defaults`) resolved with the other options over it.
Illustration illustrationFromOptions(const std::vector<OptionSpec>& declared,
                                     const OptionReader& options,
                                     const IllustrationStyle& defaults = {});

}  // namespace vsil
