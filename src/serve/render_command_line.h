#pragma once
// A `vsil render` command line as flags and values, the form in which `vsil serve` keeps the
// view: the server's own flags (from its command line), overridden by the page's parameters
// (width_near=4 -> --width-near 4), checked by parsing them with the very options `vsil render`
// registers (cli/cli_render_options.h), so the page passes the same validation as the CLI and
// the command line shown to the user is the one that was rendered.
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/cli_render_options.h"
#include "io/volume_loader.h"
#include "job/render_job.h"

namespace vsil::serve {

struct GivenFlag {
  std::string name;                 // without "--"
  std::vector<std::string> values;  // none for a switch
};

struct RenderCommandLine {
  std::string input;
  std::vector<GivenFlag> flags;  // in the order the command registers them

  // INPUT, then --name value ... (a List flag once per value).
  std::vector<std::string> arguments() const;
  // "vsil render INPUT ... --out OUT", each word quoted for a POSIX shell where it needs it.
  std::string shellText(const std::string& out) const;
  const GivenFlag* find(const std::string& name) const;
};

// What the flags describe, checked as `vsil render` checks them before reading any file.
struct CheckedRender {
  cli::RenderFlags flags;
  RenderRequest request;
  LoadOptions load;
};
// Throws InputError with the CLI's one-line message (CLI11's own errors included).
CheckedRender checkRenderCommandLine(const RenderCommandLine& line);

// The flags given on a command that ran addRenderOptions and was parsed (the `vsil serve`
// command itself), ignoring `ignored` (its own flags, --port ...).
RenderCommandLine givenRenderFlags(const CLI::App& command,
                                   const std::vector<std::string>& ignored);

// The render flags the page may set, and how. Not the input, the volume flags (--crop, --raw
// layout, limits) and the GL flags: those are the server's, fixed at start (one volume, one
// upload, one context). Text values never name files: an option that can (--rules, --style,
// --tf, --sphere-map) takes a built-in preset from the page, or the server's own value.
class PageParameters {
 public:
  explicit PageParameters(RenderCommandLine base);

  // `base` with the page's parameters (by key: width_near for --width-near; a List key may
  // repeat) put in: a value replaces the base's, an empty value (or "off" for a switch) removes
  // the flag. The flags come out in `vsil render`'s order (--technique first), whatever the
  // order of the query. Throws InputError naming the parameter for an unknown or fixed one, or a
  // value that names a file.
  RenderCommandLine apply(const std::multimap<std::string, std::string>& parameters) const;

  // The page's starting values: {key: text, or [texts] for a List; "on" for a switch}.
  nlohmann::json baseValues() const;
  // The options for the page's controls: every technique's declared options
  // (slicing/technique_table.h) and the shared render flags, with kinds, defaults and ranges;
  // the presets a file-naming option takes.
  nlohmann::json optionTable() const;
  const RenderCommandLine& base() const { return base_; }

 private:
  struct Settable {
    bool isSwitch = false;
    bool isList = false;
    std::string help;
    std::string defaultText;
    bool technique = false;  // declared in the technique table
  };
  RenderCommandLine base_;
  std::map<std::string, Settable> settable_;  // by flag name
  std::vector<std::string> fixed_;            // the server's: input, volume and GL flags
  std::vector<std::string> order_;            // every flag, as `vsil render` registers them
};

}  // namespace vsil::serve
