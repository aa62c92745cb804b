#pragma once
// Where tests find the data that lives beside the repository (../shared: the Kodak photographs,
// motion capture). Tests run through ctest, which sets GPUJ2K_SOURCE_DIR to the project root; a
// test whose data is absent skips with a message naming the path.
#include <cstdlib>
#include <filesystem>
#include <string>

namespace test_support {

inline std::filesystem::path shared_dir() {
  const char* root = std::getenv("GPUJ2K_SOURCE_DIR");
  return std::filesystem::path(root ? root : ".") / ".." / "shared";
}

inline std::filesystem::path kodak_photo(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "kodim%02d.png", index);
  return shared_dir() / "testimages" / "kodak" / name;
}

inline std::filesystem::path bvh_asset(const std::string& name) { return shared_dir() / "assets" / "bvh" / name; }

}  // namespace test_support

#define REQUIRE_SHARED_FILE(path)                                                                           \
  do {                                                                                                      \
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data " << (path) << " not found; skipping"; \
  } while (0)
