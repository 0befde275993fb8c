#include "cli/serve_command.h"

#include <atomic>
#include <cstdio>

#include "generate/export/output_folder.h"
#include "serve/server.h"

namespace exacity {

void add_serve(CLI::App& app, ServeCommand& c) {
  c.app = app.add_subcommand("serve", "Edit a sketch, generate, explore and render the city in a browser");
  c.app->add_option("SKETCH", c.sketch, "A sketch to start from, copied into the work folder with its heightmap");
  c.app->add_option("--port", c.port, "The port to listen on (0: any free one)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  c.app
      ->add_option("--host", c.host,
                   "The address to listen on; anything but 127.0.0.1 lets others on the network use the server "
                   "(docs/serve.md)")
      ->capture_default_str();
  c.app->add_option("--work", c.work, "The work folder: the sketch, its heightmap, the city and the renders")
      ->capture_default_str();
  c.app
      ->add_option("--max-render", c.max_render,
                   "The most samples one render may trace (width x height x samples per pixel, the overview's "
                   "included); a larger one is refused")
      ->check(CLI::Range(std::uint64_t(1), std::uint64_t(1) << 40))
      ->capture_default_str();
}

int run_serve(const ServeCommand& c) {
  serve::ServeOptions options;
  options.work = c.work, options.web = EXACITY_WEB_DIR, options.host = c.host, options.port = c.port;
  options.max_render = c.max_render;
  serve::CityServer server(options);
  if (!c.sketch.empty()) server.import_sketch(c.sketch);
  const int port = server.bind();
  std::atomic<int> signal{0};
  // The first Ctrl-C stops the server and cancels its job; a second one ends it at once
  // (docs/design.md, Conventions).
  on_interrupt([&](int s) {
    signal = s;
    server.stop();
  });
  const bool local = c.host == "127.0.0.1" || c.host == "localhost" || c.host == "::1";
  // The token in the address: whoever opens it (the user, who sees it here) may drive the
  // server; other pages, and other users of this machine, may not.
  std::printf("exacity: serving http://%s:%d/?token=%s (work folder %s); Ctrl-C stops\n",
              c.host.find(':') != std::string::npos ? ("[" + c.host + "]").c_str() : c.host.c_str(), port,
              server.token().c_str(), server.work_folder().string().c_str());
  if (!local)
    std::printf(
        "exacity: note: listening on %s: the traffic is not encrypted, so anyone on the network who sees the "
        "address above can replace the sketch, run generations and renders, and read what the work folder holds\n",
        c.host.c_str());
  std::fflush(stdout);
  server.run();
  on_interrupt(nullptr);  // the handler holds this function's locals
  std::fprintf(stderr, "exacity: stopping; a running job stops within its stage\n");
  server.finish_jobs();
  return signal ? 128 + signal : 0;
}

}  // namespace exacity
