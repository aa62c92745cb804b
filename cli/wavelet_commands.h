// dwtool's wavelet applications (thesis 4.7): edit, combine, decouple, deform. Thin clients of
// wavelet_apps: read, check everything, compute on the chosen backend, then write (atomically).
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace dwtool {

enum class AppCommand { Edit, Combine, Decouple, Deform };

struct AppOptions {
  AppCommand command = AppCommand::Edit;
  std::string input;
  std::string output;
  std::string detail;       // combine
  std::string illuminance;  // decouple
  std::string space;        // empty: rgb for edit, ycc for combine
  std::string fit = "resize";
  std::vector<std::string> bands;
  std::string kernel = "97";
  int levels = -1;  // -1: 5 for images, 3 for control nets
  std::string boundary = "sym";
  std::string backend = "cpu";
  int threads = 0;
  std::string gl;
  float guard = 1.0f / 64.0f;
  bool head = false;  // deform: the built-in head
  std::string mesh;   // deform: tessellated surface
  int subdivisions = 4;
  std::string picture;  // deform: rendered PNG
  bool quiet = false;
};

// Adds the four subcommands to `app`, each binding its options to `options`; returns them in the
// order of AppCommand.
std::vector<CLI::App*> add_app_commands(CLI::App& app, AppOptions& options);

// Throws std::exception with a one-line message on any failure; nothing is written unless all
// succeeded.
void run_app(const AppOptions& options);

}  // namespace dwtool
