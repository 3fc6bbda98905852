// cropsight studio: a local web application over one depth sequence (src/studio, docs/studio.md):
// review the model's candidates, label frames with its help, train and judge a model. Serves
// until Ctrl-C (SIGINT) or SIGTERM, which stop it cleanly and release the sequence's lock.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <thread>

#include "cli_common.hpp"
#include "commands.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/studio/server.hpp"

namespace cropsight::cli {

namespace studio_cmd {

struct Options {
  studio::StudioOptions studio;
  std::string data, images, models_dir, general_data;
};

// SIGINT and SIGTERM write one byte into a pipe that a watcher thread waits on; the watcher stops
// the server, and the process ends through the normal destructors (the lock is released). A
// handler, not sigwait: libraries start threads of their own when they load (OpenBLAS), and a
// signal would end the process through any of them that does not block it. The pipe's write end
// is the one thing a handler may use (write() is async-signal-safe), hence a file-level variable.
int stop_pipe_write = -1;

extern "C" void on_stop_signal(int) {
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = ::write(stop_pipe_write, &byte, 1);
}

void run(const Options& o) {
  studio::StudioOptions so = o.studio;
  if (o.data.empty() == o.images.empty()) throw Error("studio", "give exactly one of --data and --images");
  so.sequence = o.data;
  so.images = o.images;
  if (!o.studio.detector.empty() && o.images.empty()) throw Error("--detector", "proposes boxes on --images only");
  so.models_dir = o.models_dir;
  if (!o.general_data.empty() && !o.images.empty())
    throw Error("--general-data", "adds broccoli training passes, so it goes with --data, not --images");
  if (!o.general_data.empty())
    for (const auto& dir : split_list(o.general_data, "--general-data")) so.general_data.emplace_back(dir);
  studio::StudioServer server(so);
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw Error("studio", "cannot create a pipe for Ctrl-C");
  stop_pipe_write = fds[1];
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
  const std::string& folder = o.data.empty() ? o.images : o.data;
  std::printf("cropsight studio: %s, %s\n", folder.c_str(),
              !server.writable() ? "read-only (--read-only, or another studio writes this folder)"
              : o.images.empty() ? "labels are written into the sequence"
                                 : "labels are written into its cropsight-labels/ folder");
  std::printf("open %s\n(Ctrl-C stops the studio)\n", server.url().c_str());
  std::fflush(stdout);
  std::thread watcher([&server, read_end = fds[0]] {
    char byte = 0;
    while (::read(read_end, &byte, 1) < 0 && errno == EINTR) {
    }
    server.stop();
  });
  server.run();
  // run() returned: after the watcher's stop(), or because listening failed; wake the watcher in
  // the second case (a second byte is harmless in the first).
  on_stop_signal(0);
  watcher.join();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  ::close(fds[0]);
  ::close(fds[1]);
  std::printf("cropsight studio: stopped\n");
}

}  // namespace studio_cmd

void add_studio(CLI::App& app) {
  using namespace studio_cmd;
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "studio", "Review, label and train on a depth sequence or label images in the browser (docs/studio.md)");
  cmd->add_option("--data", o->data, "Depth sequence folder to review and label");
  cmd->add_option("--images", o->images, "Folder of images to label with boxes and polygons");
  cmd->add_option("--model", o->studio.model,
                  "Broccoli model name or file (default: the general model); with --images, an ONNX detector "
                  "(default: the potato preset's detector)");
  cmd->add_option("--detector", o->studio.detector,
                  "With --images: the 2D detector of detect objects (e.g. detector-grape, or a train detector model) "
                  "in place of the potato pipeline");
  cmd->add_option("--port", o->studio.port, "Port to listen on (default: a free one)")->check(CLI::Range(0, 65535));
  cmd->add_option("--bind", o->studio.bind, "Address to listen on (default 127.0.0.1: this machine only)");
  cmd->add_option("--models-dir", o->models_dir,
                  "Folder where kept models are written (default: the sequence's parent)");
  cmd->add_option("--general-data", o->general_data,
                  "Labelled passes the page may train on next to the sequence's frames (the general model's "
                  "training passes, comma separated; docs/studio.md)");
  cmd->add_flag("--read-only", o->studio.read_only, "Never write into the sequence");
  cmd->callback([o] { run(*o); });
}

}  // namespace cropsight::cli
