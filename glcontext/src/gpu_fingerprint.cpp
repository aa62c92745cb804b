#include "glcontext/gpu_fingerprint.h"

#include <algorithm>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace glc {
namespace {

namespace fs = std::filesystem;

std::string trimmed(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return "";
  const auto last = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(first, last - first + 1));
}

std::string first_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return trimmed(line);
}

// The value of the first "Key: value" line whose key is `key`.
std::string keyed_value(const fs::path& file, std::string_view key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    const auto colon = line.find(':');
    if (colon != std::string::npos && trimmed(std::string_view(line).substr(0, colon)) == key)
      return trimmed(std::string_view(line).substr(colon + 1));
  }
  return "";
}

// The sorted names in `dir` that start with `prefix`.
std::vector<std::string> entries(const fs::path& dir, std::string_view prefix) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    std::string name = e.path().filename().string();
    if (name.starts_with(prefix)) names.push_back(std::move(name));
  }
  std::sort(names.begin(), names.end());
  return names;
}

// NVIDIA's proprietary driver: "580.159.04" from "NVRM version: NVIDIA UNIX x86_64 Kernel Module
// 580.159.04  <date>", and each GPU's "Model:" line.
std::string nvidia_part(const fs::path& root) {
  const fs::path proc = root / "proc/driver/nvidia";
  std::string version = first_line(proc / "version");
  static constexpr std::string_view kModule = "Kernel Module";
  if (const auto at = version.find(kModule); at != std::string::npos) {
    version = trimmed(std::string_view(version).substr(at + kModule.size()));
    version = version.substr(0, version.find_first_of(" \t"));
  }
  std::string models;
  for (const std::string& gpu : entries(proc / "gpus", "")) {
    const std::string model = keyed_value(proc / "gpus" / gpu / "information", "Model");
    models += (models.empty() ? "" : ", ") + (model.empty() ? gpu : model);
  }
  return "nvidia " + (version.empty() ? std::string("(driver version unknown)") : version) + ": " +
         (models.empty() ? std::string("(models unknown)") : models);
}

// A DRM node: its PCI ids and kernel driver, e.g. "renderD128 0x1002:0x73bf amdgpu".
std::string drm_part(const fs::path& root, const std::string& node) {
  const fs::path device = root / "sys/class/drm" / node / "device";
  std::error_code ec;
  const fs::path driver = fs::read_symlink(device / "driver", ec);
  return node + " " + first_line(device / "vendor") + ":" + first_line(device / "device") + " " +
         (ec ? std::string("(driver unknown)") : driver.filename().string());
}

}  // namespace

std::string hardware_gpu_fingerprint(const fs::path& root) {
  std::vector<std::string> parts;
  std::error_code ec;
  if (fs::exists(root / "dev/nvidia0", ec)) parts.push_back(nvidia_part(root));
  // card* and renderD* name the same devices; the render nodes are what headless EGL opens.
  std::vector<std::string> nodes = entries(root / "dev/dri", "renderD");
  if (nodes.empty()) nodes = entries(root / "dev/dri", "card");
  const bool kernel_drivers = !nodes.empty() || fs::exists(root / "dev/dxg", ec);
  for (const std::string& node : nodes) parts.push_back("drm " + drm_part(root, node));
  if (fs::exists(root / "dev/dxg", ec)) parts.push_back("dxg");
  // DRM and WSL drivers come with the kernel: its release stands for their version.
  if (kernel_drivers) parts.push_back("kernel " + first_line(root / "proc/sys/kernel/osrelease"));
  std::string line;
  for (const std::string& part : parts) line += (line.empty() ? "" : "; ") + part;
  return line;
}

}  // namespace glc
