#include "serve/frame_server.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <future>
#include <iostream>
#include <thread>

#include <sys/socket.h>

#include <httplib.h>

#include "core/error.h"
#include "core/image_file.h"
#include "core/json_input.h"
#include "core/options.h"
#include "serve/frame_queue.h"

namespace vsil::serve {

std::string_view embeddedPageFile(std::string_view path);  // generated (src/serve/CMakeLists.txt)

namespace {

// What the copied command line writes; the page's "save PNG" offers the same name.
constexpr const char* kCommandOut = "view.png";

void answerText(httplib::Response& response, int status, const std::string& text) {
  response.status = status;
  response.set_content(text + "\n", "text/plain; charset=utf-8");
}

// Constant time in the token's length: the comparison does not say how much of it matched.
bool sameToken(const std::string& given, const std::string& token) {
  if (given.size() != token.size()) return false;
  unsigned char difference = 0;
  for (std::size_t i = 0; i < token.size(); ++i) difference |= given[i] ^ token[i];
  return difference == 0;
}

}  // namespace

bool isLoopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

// Connections served at once (frames still render one at a time: LatestOnlyQueue).
constexpr std::size_t kConnectionWorkers = 64;

struct FrameServer::Impl {
  ServeOptions options;
  PageParameters page;
  CheckedRender base;
  httplib::Server http;
  int port = 0;
  LatestOnlyQueue queue;
  std::thread renderThread;
  std::unique_ptr<RenderJob> job;  // lives on renderThread
  nlohmann::json volumeFacts;

  explicit Impl(ServeOptions given)
      : options(std::move(given)),
        page(options.command),
        base(checkRenderCommandLine(options.command)) {}

  // Pixels × slices per voxel of a render.
  static double frameSamples(const CheckedRender& render) {
    const RenderSettings& settings = render.request.settings;
    return double(settings.size.x) * double(settings.size.y) * settings.samplesPerVoxel;
  }

  // A page's frame within the server's bound (ServeOptions::maxFrameSamples).
  void checkFrameSamples(const CheckedRender& render) const {
    const double bound = std::max(options.maxFrameSamples, frameSamples(base));
    if (frameSamples(render) > bound) {
      const RenderSettings& settings = render.request.settings;
      throwInputError("--size " + std::to_string(settings.size.x) + "x" +
                          std::to_string(settings.size.y) + " at --sampling " +
                          formatNumber(settings.samplesPerVoxel),
                      "more pixels x sampling than this server renders per frame (" +
                          formatNumber(bound) + "; vsil serve --max-frame-samples)");
    }
  }

  void startRenderer() {
    std::promise<void> ready;
    std::future<void> started = ready.get_future();
    renderThread = std::thread([this, &ready] {
      try {
        job = std::make_unique<RenderJob>(cli::toContextOptions(base.flags.gl));
        // The volume once: every frame renders the same upload.
        LoadOptions load = RenderJob::loadOptionsFor(base.request, base.load);
        const Volume& volume = job->setVolume(loadVolume(options.command.input, load),
                                              options.command.input, load.limits.maxTextureBytes);
        const ValueRange range = valueRange(volume);
        volumeFacts = {{"value_range", {range.min, range.max}},
                       {"default_iso", defaultIso(volume)},
                       {"dims", {volume.dims.x, volume.dims.y, volume.dims.z}}};
        ready.set_value();
      } catch (...) {
        job.reset();
        ready.set_exception(std::current_exception());
        return;
      }
      queue.workerLoop();
      job.reset();  // the GL context ends on the thread it was made on
    });
    try {
      started.get();
    } catch (...) {
      renderThread.join();
      throw;
    }
  }

  void frame(const httplib::Request& request, httplib::Response& response) {
    const auto received = std::chrono::steady_clock::now();
    std::multimap<std::string, std::string> parameters;
    for (const auto& [key, value] : request.params) {
      if (key != "token") parameters.emplace(key, value);
    }
    RenderCommandLine line;
    CheckedRender checked;
    try {
      line = page.apply(parameters);
      checked = checkRenderCommandLine(line);
      checkFrameSamples(checked);
    } catch (const InputError& e) {
      return answerText(response, 400, e.what());
    }
    std::vector<std::uint8_t> png;
    std::vector<std::string> warnings;
    double renderMs = 0;
    bool ran = false;
    try {
      ran = queue.run([&] {
        const auto start = std::chrono::steady_clock::now();
        RenderOutput output = job->render(checked.request, checked.load.limits);
        png = encodePng(output.image);
        warnings = output.warnings;
        renderMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
      });
    } catch (const InputError& e) {
      return answerText(response, 400, e.what());
    } catch (const std::exception& e) {
      std::cerr << "vsil serve: error: " << e.what() << "\n";
      return answerText(response, 500, std::string("internal error: ") + e.what());
    }
    if (!ran) return answerText(response, 409, "superseded by a newer view");
    std::string warningText;
    for (const auto& warning : warnings) warningText += (warningText.empty() ? "" : "; ") + warning;
    response.set_header("X-Vsil-Command", line.shellText(kCommandOut));
    response.set_header("X-Vsil-Render-Ms", std::to_string(renderMs));
    response.set_header("X-Vsil-Total-Ms",
                        std::to_string(std::chrono::duration<double, std::milli>(
                                           std::chrono::steady_clock::now() - received)
                                           .count()));
    if (!warningText.empty()) response.set_header("X-Vsil-Warnings", warningText);
    response.set_header("Cache-Control", "no-store");
    response.set_content(std::string(png.begin(), png.end()), "image/png");
  }

  void routes() {
    http.set_pre_routing_handler(
        [this](const httplib::Request& request, httplib::Response& response) {
          // The page's script is static and holds nothing of the server's: the page at
          // /?token=... loads it by a plain <script src>.
          if (options.token.empty() || request.path == "/serve.js") {
            return httplib::Server::HandlerResponse::Unhandled;
          }
          std::string given = request.get_param_value("token");
          if (given.empty()) given = request.get_header_value("X-Vsil-Token");
          if (sameToken(given, options.token)) return httplib::Server::HandlerResponse::Unhandled;
          answerText(response, 403, "missing or wrong token (?token=...)");
          return httplib::Server::HandlerResponse::Handled;
        });
    const auto file = [](const char* path, const char* type) {
      return [path, type](const httplib::Request&, httplib::Response& response) {
        const std::string_view text = embeddedPageFile(path);
        response.set_content(std::string(text), type);
      };
    };
    http.Get("/", file("index.html", "text/html; charset=utf-8"));
    http.Get("/serve.js", file("serve.js", "text/javascript; charset=utf-8"));
    http.Get("/api/options", [this](const httplib::Request&, httplib::Response& response) {
      response.set_content(jsonText(page.optionTable()), "application/json");
    });
    http.Get("/api/state", [this](const httplib::Request&, httplib::Response& response) {
      nlohmann::json state = volumeFacts;
      state["input"] = options.command.input;
      state["values"] = page.baseValues();
      state["command"] = options.command.shellText(kCommandOut);
      state["technique"] = base.flags.technique;
      response.set_content(jsonText(state), "application/json");
    });
    http.Get("/frame", [this](const httplib::Request& request, httplib::Response& response) {
      frame(request, response);
    });
    // Requests are small: a query string, no body.
    http.set_payload_max_length(64 * 1024);
    // A connection holds a worker while its request comes in: eight idle or half-sent ones
    // starved the library's default pool (8 workers, 5 s waits) and the page with it. Many
    // workers (they sleep in poll), short waits for a request and between kept-alive ones.
    http.new_task_queue = [] { return new httplib::ThreadPool(kConnectionWorkers); };
    http.set_read_timeout(2, 0);
    http.set_keep_alive_timeout(2);
  }

  void bind() {
    // The library's default sockets add SO_REUSEPORT, with which a second server on a port in
    // use started too and the kernel split the requests between the two. SO_REUSEADDR alone
    // lets a restarted server take its port back from connections still closing.
    http.set_socket_options([](socket_t socket) {
      int yes = 1;
      setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    });
    if (options.port == 0) {
      port = http.bind_to_any_port(options.bind);
    } else {
      port = http.bind_to_port(options.bind, options.port) ? options.port : -1;
    }
    if (port <= 0) {
      throwInputError("--port " + std::to_string(options.port),
                      "cannot listen on " + options.bind + " (in use, or not an address here)");
    }
  }
};

void checkServeOptions(const ServeOptions& options) {
  if (!isLoopback(options.bind) && options.token.empty()) {
    throwInputError("--bind " + options.bind,
                    "not a loopback address: give --token too (anyone who reaches the port could "
                    "render)");
  }
  if (options.port < 0 || options.port > 65535) {
    throwInputError("--port", std::to_string(options.port) + " is not a port (0..65535)");
  }
  checkRenderCommandLine(options.command);
  if (!(options.maxFrameSamples >= 1) || !std::isfinite(options.maxFrameSamples)) {
    throwInputError("--max-frame-samples", "must be a finite number, at least 1");
  }
}

FrameServer::FrameServer(ServeOptions options) {
  checkServeOptions(options);
  impl_ = std::make_unique<Impl>(std::move(options));
  impl_->routes();
  impl_->bind();
  impl_->startRenderer();
}

FrameServer::~FrameServer() {
  stop();
  impl_->queue.close();
  if (impl_->renderThread.joinable()) impl_->renderThread.join();
}

int FrameServer::port() const {
  return impl_->port;
}

std::string FrameServer::url() const {
  const std::string& host = impl_->options.bind;
  const bool v6 = host.find(':') != std::string::npos;
  std::string address =
      "http://" + (v6 ? "[" + host + "]" : host) + ":" + std::to_string(impl_->port) + "/";
  const std::string& token = impl_->options.token;
  if (token.empty()) return address;
  // RFC 3986: all but the unreserved characters percent-encoded (a token holding & or %).
  address += "?token=";
  for (const unsigned char c : token) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~') {
      address += char(c);
    } else {
      static const char kHex[] = "0123456789ABCDEF";
      address += {'%', kHex[c >> 4], kHex[c & 15]};
    }
  }
  return address;
}

void FrameServer::listen() {
  impl_->http.listen_after_bind();
}

void FrameServer::stop() {
  impl_->http.stop();
}

}  // namespace vsil::serve
