// vsil serve: the render flags of `vsil render`, interactive in a browser — a page that orbits,
// zooms and tunes the technique's options, rendered here (serve/frame_server.h).
#include <csignal>
#include <iostream>
#include <memory>

#include "cli/cli_render_options.h"
#include "cli/commands.h"
#include "serve/frame_server.h"

namespace vsil::cli {
namespace {

struct ServeFlags {
  std::string bind = "127.0.0.1";
  int port = 8080;
  std::string token;
  double maxFrameSamples = serve::ServeOptions::kDefaultMaxFrameSamples;
};

serve::FrameServer* runningServer = nullptr;

// Ctrl-C and SIGTERM end the server cleanly (the render thread joins, the GL context ends).
extern "C" void stopServing(int) {
  if (runningServer) runningServer->stop();
}

void run(const CLI::App& command, const ServeFlags& flags) {
  serve::ServeOptions options;
  options.command =
      serve::givenRenderFlags(command, {"bind", "port", "token", "max-frame-samples"});
  options.bind = flags.bind;
  options.port = flags.port;
  options.token = flags.token;
  options.maxFrameSamples = flags.maxFrameSamples;
  serve::checkServeOptions(options);
  if (validateOnly()) return;

  serve::FrameServer server(std::move(options));
  std::cout << "vsil serve: " << server.url() << std::endl;
  runningServer = &server;
  std::signal(SIGINT, stopServing);
  std::signal(SIGTERM, stopServing);
  server.listen();
  runningServer = nullptr;
}

const CommandRegistration registerServeCommand(50, [](CLI::App& app) {
  auto renderFlags = std::make_shared<RenderFlags>();
  auto flags = std::make_shared<ServeFlags>();
  CLI::App* command = app.add_subcommand(
      "serve",
      "Serve a page that renders interactively: drag to orbit, wheel to zoom, the "
      "technique's options as controls; the frames are rendered here");
  addRenderOptions(*command, *renderFlags);
  command->add_option("--port", flags->port, "TCP port (0: any free one, printed)")
      ->capture_default_str();
  command
      ->add_option("--bind", flags->bind,
                   "address to listen on; other than loopback only with --token")
      ->capture_default_str();
  command->add_option("--token", flags->token,
                      "a secret every request must carry (?token=...); needed to bind "
                      "beyond loopback");
  command
      ->add_option("--max-frame-samples", flags->maxFrameSamples,
                   "the most pixels x --sampling a page may ask of one frame (a frame's time "
                   "grows with both; at least what the command line asks)")
      ->capture_default_str();
  // The callback owns renderFlags too: addRenderOptions bound the options to its members
  // (run reads the given flags from the command, but CLI11 still stores into them).
  command->callback([command, flags, renderFlags] { run(*command, *flags); });
});

}  // namespace
}  // namespace vsil::cli
