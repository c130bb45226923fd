#pragma once
// `vsil serve`: one page and a frame endpoint over HTTP (Debian's cpp-httplib), one renderer
// and one volume upload for every frame. Routes:
//   GET /               the page (src/serve/page, embedded at build time)
//   GET /serve.js       its script
//   GET /api/options    the option table as JSON (PageParameters::optionTable): the page builds
//                       its controls from it, so a new option appears there by itself
//   GET /api/state      the server's view: input, starting values, the volume's value range
//   GET /frame?K=V&...  a PNG of the server's command line with the page's parameters
//                       (PageParameters::apply); headers X-Vsil-Command (the `vsil render`
//                       line that gives the same bytes) and X-Vsil-Render-Ms. Bad parameters:
//                       400 with the CLI's one-line message; a frame replaced by a newer one
//                       before it started: 409.
// With a token every request carries it (?token=T or the header X-Vsil-Token), else 403.
#include <memory>
#include <string>

#include "serve/render_command_line.h"

namespace vsil::serve {

struct ServeOptions {
  RenderCommandLine command;  // INPUT and the render flags as given to `vsil serve`
  std::string bind = "127.0.0.1";
  int port = 8080;  // 0: any free port (port() says which)
  std::string token;
  // The most pixels × --sampling (slices per voxel) a page may ask of one frame, or what the
  // command line itself asks if that is more: a frame's time grows with both, and one request
  // holds the only renderer for as long as it takes.
  double maxFrameSamples = kDefaultMaxFrameSamples;
  static constexpr double kDefaultMaxFrameSamples = 2048.0 * 2048.0 * 2.0;
};

// Whether `host` is a loopback address (127.0.0.0/8, ::1, localhost): the page is then
// reachable from this machine only and needs no token.
bool isLoopback(const std::string& host);

// What FrameServer checks before any work: a non-loopback bind needs a token, the port is one,
// the command line passes `vsil render`'s checks. Throws InputError naming the flag.
void checkServeOptions(const ServeOptions& options);

class FrameServer {
 public:
  // Checks the options (a non-loopback bind needs a token; the command line as `vsil render`
  // checks it), binds the port, creates the GL context and uploads the volume on the render
  // thread. Throws InputError (bad flags, input, port in use) or UnavailableError (no GL).
  explicit FrameServer(ServeOptions options);
  ~FrameServer();
  FrameServer(const FrameServer&) = delete;
  FrameServer& operator=(const FrameServer&) = delete;

  int port() const;
  // The page's address: http://HOST:PORT/, with ?token=... (percent-encoded) when one is asked.
  std::string url() const;
  // Answers requests until stop() (from any thread).
  void listen();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vsil::serve
