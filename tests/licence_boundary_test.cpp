// The codec and wavelet tools stay MIT: nothing of espeak-ng (GPL-3.0) or of FFmpeg's libraries
// and x264 (GPL as built by Debian) may end up in them, whatever they link for other reasons
// (dwtool links the performer's static library for its procedural head and mesh writers, from
// which only those objects may be pulled). Checked on the built programs: their dynamic
// dependencies (readelf -d) and their symbols (nm).
#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <memory>
#include <string>

namespace {

std::string output_of(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return {};
  std::string out;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe.get())) out += buffer.data();
  return out;
}

// The program's symbol names, demangled, in lower case.
std::string lower_symbols(const std::string& program) {
  std::string symbols = output_of("nm -C '" + program + "' 2>&1");
  for (char& c : symbols) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return symbols;
}

TEST(LicenceBoundary, CodecAndWaveletToolsHoldNoGplCode) {
  const char* programs[] = {J2KENC_PATH, DWTOOL_PATH, IMGPSNR_PATH};
  const char* forbidden_libraries[] = {"espeak", "avcodec", "avformat", "avutil", "swscale", "swresample", "x264"};
  for (const char* program : programs) {
    SCOPED_TRACE(program);
    const std::string needed = output_of(std::string("readelf -d '") + program + "' 2>&1");
    ASSERT_NE(needed.find("NEEDED"), std::string::npos) << needed;  // readelf ran and saw the program
    for (const char* library : forbidden_libraries) EXPECT_EQ(needed.find(library), std::string::npos) << library;
    const std::string symbols = lower_symbols(program);
    ASSERT_NE(symbols.find("main"), std::string::npos) << symbols.substr(0, 200);
    EXPECT_EQ(symbols.find("espeak"), std::string::npos);
    EXPECT_EQ(symbols.find("avcodec_"), std::string::npos);
    EXPECT_EQ(symbols.find("videowriter"), std::string::npos);
  }
  // The same checks see them where they are: the performer links both.
  const std::string performer_needed = output_of(std::string("readelf -d '") + PERFORMER_PATH + "' 2>&1");
  EXPECT_NE(performer_needed.find("espeak"), std::string::npos);
  EXPECT_NE(performer_needed.find("avcodec"), std::string::npos);
  EXPECT_NE(lower_symbols(PERFORMER_PATH).find("espeak"), std::string::npos);
}

}  // namespace
