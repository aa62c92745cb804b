#include "gltf_load.h"

#include <cstring>
#include <fstream>
#include <string>

#include "base/one_line.h"
#include "performer/gltf_skin.h"

namespace performer::detail {

namespace {

bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

}  // namespace

tinygltf::Model load_gltf_model(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw GltfError(file, "cannot open file");
  // Binary glTF starts with the magic "glTF", whatever the file is called.
  char magic[4] = {};
  probe.read(magic, sizeof magic);
  const bool binary = probe.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;
  probe.close();
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, file)
                         : loader.LoadASCIIFromFile(&model, &err, &warn, file);
  if (!ok)
    throw GltfError(
        file, "not a readable glTF 2.0 file: " + (err.empty() ? std::string("unknown error") : base::one_line(err)));
  return model;
}

}  // namespace performer::detail
