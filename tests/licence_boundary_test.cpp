// The codec and wavelet tools stay MIT: nothing of espeak-ng (GPL-3.0) or of FFmpeg's libraries
// and x264 (GPL as built by Debian) may end up in them, whatever they link for other reasons
// (dwtool links the performer's head and mesh libraries for its procedural head and mesh writers).
// Nor in the performer's parts other than speech (espeak-ng) and video (FFmpeg): BVH, skinning,
// the face, the body, glTF and the GPU renderer link no GPL code. Checked on built programs: their
// dynamic dependencies (readelf -d) and their symbols (nm). The performer's parts are checked
// through probe programs (tests/licence_probes/) linked against them alone with --no-as-needed, so
// that every shared library in a part's link interface shows as a dependency.
#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <memory>
#include <string>

namespace {

// Whether the performer was built with speech (GPUJ2K_PERFORMER_SPEECH), i.e. links espeak-ng.
constexpr bool kPerformerSpeaks = PERFORMER_SPEAKS;

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

// The program's dynamic dependencies: the NEEDED lines of readelf's dynamic section, alone (the
// other lines hold addresses, where "x264" can occur as hex digits, "0x26436").
std::string needed_libraries(const std::string& program) {
  return output_of("readelf -d '" + program + "' 2>&1 | grep NEEDED");
}

// No GPL library among the program's dependencies and none of their code in it.
void expect_no_gpl(const std::string& program) {
  SCOPED_TRACE(program);
  const char* forbidden_libraries[] = {"espeak", "avcodec", "avformat", "avutil", "swscale", "swresample", "x264"};
  const std::string needed = needed_libraries(program);
  ASSERT_NE(needed.find("NEEDED"), std::string::npos) << needed;  // readelf ran and saw the program
  for (const char* library : forbidden_libraries) EXPECT_EQ(needed.find(library), std::string::npos) << library;
  const std::string symbols = lower_symbols(program);
  ASSERT_NE(symbols.find("main"), std::string::npos) << symbols.substr(0, 200);
  EXPECT_EQ(symbols.find("espeak"), std::string::npos);
  EXPECT_EQ(symbols.find("avcodec_"), std::string::npos);
  EXPECT_EQ(symbols.find("videowriter"), std::string::npos);
}

TEST(LicenceBoundary, CodecAndWaveletToolsHoldNoGplCode) {
  for (const char* program : {J2KENC_PATH, DWTOOL_PATH, IMGPSNR_PATH}) expect_no_gpl(program);
  // The same checks see them where they are: the performer links FFmpeg, and espeak-ng when it
  // speaks.
  const std::string performer_needed = needed_libraries(PERFORMER_PATH);
  EXPECT_NE(performer_needed.find("avcodec"), std::string::npos);
  EXPECT_EQ(performer_needed.find("espeak") != std::string::npos, kPerformerSpeaks);
  // espeak-ng's own API (espeak_ng_Initialize, ...): our EspeakTts is named after it in both builds.
  EXPECT_EQ(lower_symbols(PERFORMER_PATH).find("espeak_ng_") != std::string::npos, kPerformerSpeaks);
}

// Kinematics (BVH, FK, IK, SSD weights, skinning), visemes, mesh, head, face, body, character, glTF
// and render: MIT code linking only permissive libraries.
TEST(LicenceBoundary, PerformerPartsOtherThanSpeechAndVideoHoldNoGplCode) {
  expect_no_gpl(PERFORMER_MIT_PARTS_PATH);
  // The probe holds those parts' code: the BVH reader, the procedural head, the character, glTF.
  const std::string symbols = lower_symbols(PERFORMER_MIT_PARTS_PATH);
  for (const char* function : {"performer::read_bvh", "performer::build_character", "performer::load_gltf_avatar",
                               "performer::build_procedural_head"})
    EXPECT_NE(symbols.find(function), std::string::npos) << function;
  // And its whole link line is among its dependencies: TinyGLTF (glTF's) is there.
  const std::string needed = needed_libraries(PERFORMER_MIT_PARTS_PATH);
  EXPECT_NE(needed.find("tinygltf"), std::string::npos) << needed;
}

// espeak-ng is linked by the speech part alone, and only when speech is built: the same probe
// inspection that finds nothing in the other parts finds it there.
TEST(LicenceBoundary, SpeechLinksEspeakNgExactlyWhenBuilt) {
  const std::string needed = needed_libraries(PERFORMER_SPEECH_PART_PATH);
  ASSERT_NE(needed.find("NEEDED"), std::string::npos) << needed;
  EXPECT_EQ(needed.find("espeak") != std::string::npos, kPerformerSpeaks) << needed;
  EXPECT_EQ(needed.find("avcodec"), std::string::npos) << needed;
}

}  // namespace
