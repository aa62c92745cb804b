// performer: the virtual performer from the command line.
//
//   performer info --bvh FILE    what a motion capture file holds
//
// Every failure is one line on stderr starting "performer: " and a non-zero exit: 2 for a command
// line that does not parse, 1 for anything that goes wrong running it.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

#include "info.h"
#include "performer/bvh.h"

namespace {

// CLI11 messages may span lines; the contract is one line.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "performer: skeletal animation from motion capture (BVH)\n\n"
      "Example:\n"
      "  performer info --bvh walk.bvh\n"};
  app.require_subcommand(1);
  std::string bvh_path;
  CLI::App* info = app.add_subcommand("info", "print a BVH file's joints, channels, frame count and duration");
  info->add_option("--bvh", bvh_path, "BVH motion capture file")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "performer: %s\n", one_line(e.what()).c_str());
    return 2;
  }

  try {
    if (info->parsed()) {
      const performer::Bvh bvh = performer::read_bvh(bvh_path);
      performer::cli::print_info(bvh, bvh_path, stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "performer: %s\n", one_line(e.what()).c_str());
    return 1;
  }
  return 0;
}
