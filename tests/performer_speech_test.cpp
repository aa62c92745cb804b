// Tests for the performer's text to speech: espeak-ng speaking each language, the phoneme timeline
// it reports, the espeak-ng phoneme -> viseme mapping files (every phoneme of sample sentences
// must map), the WAV writer and reader, and the errors for bad text and bad mapping files.

#include <gtest/gtest.h>

#include "support/scratch_dir.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "performer/espeak_tts.h"
#include "performer/espeak_visemes.h"
#include "performer/speech.h"
#include "performer/speech_visemes.h"
#include "performer/viseme_error.h"
#include "performer/viseme_library.h"
#include "performer/wav.h"
#include "performer/weights_visemes.h"

namespace fs = std::filesystem;
using performer::EspeakTts;
using performer::EspeakVisemeMap;
using performer::PhonemeMark;
using performer::PhonemeRole;
using performer::Speech;
using performer::TimedPhoneme;
using performer::TimedViseme;
using performer::UnmappedSymbolError;
using performer::VisemeDataError;
using performer::VisemeLibrary;

namespace {

constexpr double kEdgeTolerance = 0.050;  // seconds

const VisemeLibrary& library() {
  static const VisemeLibrary lib = VisemeLibrary::load_default();
  return lib;
}

EspeakTts& tts() {
  static EspeakTts engine;
  return engine;
}

// The engine's tests; they skip in a build without espeak-ng (GPUJ2K_PERFORMER_SPEECH off), where
// the mapping files, phoneme timelines and WAV files are still tested.
class EspeakTtsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!EspeakTts::built()) GTEST_SKIP() << "speech was not built (GPUJ2K_PERFORMER_SPEECH=OFF): no espeak-ng to test";
  }
};

const EspeakVisemeMap& mapping(const std::string& voice) {
  static std::map<std::string, EspeakVisemeMap> maps;
  auto it = maps.find(voice);
  if (it == maps.end()) it = maps.emplace(voice, performer::load_default_espeak_visemes(voice, library())).first;
  return it->second;
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

// Runs `f`, which must throw E; returns what() for further checks.
template <class E>
std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no exception";
  return {};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The visemes that are not the closed face: what a listener sees of the words themselves.
std::vector<int> open_visemes(const std::vector<TimedViseme>& visemes) {
  std::vector<int> ids;
  for (const TimedViseme& v : visemes)
    if (v.viseme != 0) ids.push_back(v.viseme);
  return ids;
}

// ---------------------------------------------------------------------------------------------
// Sample sentences: every phoneme espeak-ng speaks for them must map to a viseme.

struct Sample {
  std::string language;
  std::vector<std::string> sentences;
};

std::vector<Sample> samples() {
  return {
      {"yue",
       {"你好，我係學生", "今日天氣好好，我哋去公園散步啦。", "佢食咗飯未呀？唔該晒！",
        "香港嘅夜景好靚，維多利亞港兩岸都係燈。"}},
      {"cmn-latn-pinyin",
       {"ni3 hao3, wo3 shi4 xue2 sheng1", "jin1 tian1 tian1 qi4 hen3 hao3, wo3 men5 qu4 gong1 yuan2 san4 bu4 ba5.",
        "lü4 se4 de5 shu4 ye4 zai4 feng1 zhong1 piao1 dong4, xiao3 niao3 zai4 chuang1 wai4 chang4 ge1.",
        "er4 shi2 ge4 ren2 zuo4 che1 qu4 bei3 jing1 kan4 chang2 cheng2, jue2 de5 hen3 qiong2 que4 ye3 xiong2 wei3."}},
      {"ja",
       {"こんにちは、わたしはがくせいです。",
        "いろはにほへと ちりぬるを わかよたれそ つねならむ うゐのおくやま けふこえて あさきゆめみし ゑひもせす",
        "きょうはいいてんきですね。コーヒーをのみませんか？", "ふじさんにのぼって、しゃしんをとりました。"}},
      {"en-us",
       {"The quick brown fox jumps over the lazy dog.", "Sphinx of black quartz, judge my vow.",
        "How vexingly quick daft zebras jump!", "The five boxing wizards jump quickly."}},
  };
}

void expect_timeline(const Speech& speech, const std::string& what) {
  ASSERT_GT(speech.sample_rate, 0) << what;
  ASSERT_FALSE(speech.samples.empty()) << what;
  ASSERT_FALSE(speech.phonemes.empty()) << what;
  const auto& ph = speech.phonemes;
  for (std::size_t i = 0; i < ph.size(); ++i) {
    EXPECT_GE(ph[i].duration, 0.0) << what << ": phoneme " << i << " '" << ph[i].name << "'";
    if (i + 1 < ph.size()) {
      EXPECT_LE(ph[i].start, ph[i + 1].start) << what << ": phonemes out of order at " << i;
      EXPECT_LE(ph[i].end(), ph[i + 1].start + 1e-9) << what << ": phonemes overlap at " << i;
    }
  }
  EXPECT_GE(ph.front().start, 0.0) << what;
  EXPECT_LE(ph.front().start, kEdgeTolerance) << what << ": first phoneme '" << ph.front().name << "'";
  EXPECT_NEAR(ph.back().end(), speech.duration(), kEdgeTolerance) << what;
}

void expect_wav_round_trip(const Speech& speech, const std::string& what) {
  test_support::ScratchDir dir("performer_speech");
  const fs::path file = dir / "speech.wav";
  performer::write_wav(file, speech.sample_rate, speech.samples);
  EXPECT_EQ(fs::file_size(file), 44 + 2 * speech.samples.size()) << what;
  const performer::WavAudio back = performer::read_wav(file);
  EXPECT_EQ(back.sample_rate, speech.sample_rate) << what;
  ASSERT_EQ(back.samples.size(), speech.samples.size()) << what;
  EXPECT_TRUE(back.samples == speech.samples) << what;
}

TEST_F(EspeakTtsTest, LanguagesAreTheFourVoices) {
  EXPECT_EQ(tts().languages(), (std::vector<std::string>{"yue", "cmn-latn-pinyin", "ja", "en-us"}));
}

TEST_F(EspeakTtsTest, SampleSentencesSpeakMapAndWrite) {
  for (const Sample& sample : samples()) {
    const EspeakVisemeMap& map = mapping(sample.language);
    for (const std::string& sentence : sample.sentences) {
      const std::string what = sample.language + " \"" + sentence + "\"";
      const Speech speech = tts().speak(sentence, sample.language);
      expect_timeline(speech, what);
      for (const TimedPhoneme& p : speech.phonemes)
        EXPECT_NE(performer::find_espeak_visemes(map, p.name), nullptr)
            << what << ": espeak-ng phoneme '" << p.name << "' is not in " << map.file;
      std::vector<TimedViseme> visemes;
      ASSERT_NO_THROW(visemes = performer::speech_visemes(speech.phonemes, map)) << what;
      EXPECT_GE(visemes.size(), speech.phonemes.size()) << what;
      EXPECT_GT(open_visemes(visemes).size(), speech.phonemes.size() / 3) << what << ": mostly closed";
      // The sequence must be one the weight functions accept (ordered, IDs in the set).
      EXPECT_NO_THROW(performer::check_viseme_sequence(visemes, library().viseme_count())) << what;
      expect_wav_round_trip(speech, what);
    }
  }
}

TEST_F(EspeakTtsTest, CantoneseNeiHouIsNEiHOu) {
  const Speech speech = tts().speak("你好", "yue");
  std::vector<std::string> spoken;
  for (const TimedPhoneme& p : speech.phonemes)
    if (!p.name.starts_with('_')) spoken.push_back(p.name);
  // espeak-ng speaks the finals ei and ou as single phonemes...
  EXPECT_EQ(spoken, (std::vector<std::string>{"n", "ei", "h", "ou"}));
  // ...which the mapping splits into the table's nucleus and coda.
  const VisemeLibrary& lib = library();
  const std::vector<int> expected = {
      lib.viseme_for("yue", "n", PhonemeRole::onset),   lib.viseme_for("yue", "e", PhonemeRole::nucleus),
      lib.viseme_for("yue", "i", PhonemeRole::coda),    lib.viseme_for("yue", "h", PhonemeRole::onset),
      lib.viseme_for("yue", "o", PhonemeRole::nucleus), lib.viseme_for("yue", "u", PhonemeRole::coda),
  };
  EXPECT_EQ(open_visemes(performer::speech_visemes(speech.phonemes, mapping("yue"))), expected);
}

TEST_F(EspeakTtsTest, MandarinNiHaoFromPinyin) {
  const Speech speech = tts().speak("ni3 hao3", "cmn-latn-pinyin");
  const VisemeLibrary& lib = library();
  const std::vector<int> expected = {
      lib.viseme_for("cmn", "n"),
      lib.viseme_for("cmn", "i", PhonemeRole::nucleus),
      lib.viseme_for("cmn", "h", PhonemeRole::onset),
      lib.viseme_for("cmn", "a", PhonemeRole::nucleus),
      lib.viseme_for("cmn", "o", PhonemeRole::nucleus),
  };
  EXPECT_EQ(open_visemes(performer::speech_visemes(speech.phonemes, mapping("cmn-latn-pinyin"))), expected);
}

TEST_F(EspeakTtsTest, SplitPhonemeSharesItsTimeEvenly) {
  const Speech speech = tts().speak("你好", "yue");
  const auto ei = std::find_if(speech.phonemes.begin(), speech.phonemes.end(),
                               [](const TimedPhoneme& p) { return p.name == "ei"; });
  ASSERT_NE(ei, speech.phonemes.end());
  const std::vector<TimedViseme> two = performer::speech_visemes(std::span(&*ei, 1), mapping("yue"));
  ASSERT_EQ(two.size(), 2u);
  EXPECT_DOUBLE_EQ(two[0].start, ei->start);
  EXPECT_NEAR(two[0].duration, ei->duration / 2, 1e-12);
  EXPECT_NEAR(two[1].start, two[0].end(), 1e-12);
  EXPECT_NEAR(two[1].end(), ei->end(), 1e-12);
}

// espeak-ng carries synthesis state from call to call, so the same text is not bit-identical
// twice (a few samples, a millisecond, apart); the words and their timing are the same.
void expect_same_speech(const Speech& a, const Speech& b) {
  EXPECT_NEAR(static_cast<double>(a.samples.size()), static_cast<double>(b.samples.size()), 0.01 * b.samples.size());
  ASSERT_EQ(a.phonemes.size(), b.phonemes.size());
  for (std::size_t i = 0; i < a.phonemes.size(); ++i) {
    EXPECT_EQ(a.phonemes[i].name, b.phonemes[i].name);
    EXPECT_NEAR(a.phonemes[i].start, b.phonemes[i].start, 0.005);
  }
}

TEST_F(EspeakTtsTest, ConcurrentCallsAreSerialised) {
  const Speech mandarin = tts().speak("ni3 hao3", "cmn-latn-pinyin");
  const Speech cantonese = tts().speak("你好", "yue");
  std::vector<Speech> results(4);
  std::vector<std::thread> workers;
  for (std::size_t i = 0; i < results.size(); ++i)
    workers.emplace_back([&results, i] {
      // Separate EspeakTts objects share the one espeak-ng; alternate voices to force switches.
      results[i] = i % 2 == 0 ? EspeakTts().speak("ni3 hao3", "cmn-latn-pinyin") : EspeakTts().speak("你好", "yue");
    });
  for (std::thread& w : workers) w.join();
  for (std::size_t i = 0; i < results.size(); ++i) expect_same_speech(results[i], i % 2 == 0 ? mandarin : cantonese);
}

// ---------------------------------------------------------------------------------------------
// Bad input.

TEST_F(EspeakTtsTest, UnknownLanguageNamesTheLanguagesThereAre) {
  const std::string m = message_of<std::invalid_argument>([] { tts().speak("hello", "fr"); });
  EXPECT_TRUE(contains(m, "'fr'")) << m;
  for (const char* language : {"yue", "cmn-latn-pinyin", "ja", "en-us"}) EXPECT_TRUE(contains(m, language)) << m;
}

TEST_F(EspeakTtsTest, EmptyTextIsRefused) {
  EXPECT_TRUE(contains(message_of<std::invalid_argument>([] { tts().speak("", "en-us"); }), "empty"));
  EXPECT_TRUE(contains(message_of<std::invalid_argument>([] { tts().speak(" \t\n", "yue"); }), "empty"));
}

TEST_F(EspeakTtsTest, TextWithNothingToSayIsRefused) {
  const std::string m = message_of<std::invalid_argument>([] { tts().speak("...", "en-us"); });
  EXPECT_TRUE(contains(m, "nothing to say")) << m;
  EXPECT_TRUE(contains(message_of<std::invalid_argument>([] { tts().speak("。，", "yue"); }), "nothing to say"));
}

TEST_F(EspeakTtsTest, HanziToPinyinVoiceIsRefused) {
  const std::string m = message_of<std::invalid_argument>([] { tts().speak("ni3 hao3 你好", "cmn-latn-pinyin"); });
  EXPECT_TRUE(contains(m, "cmn-latn-pinyin")) << m;
  EXPECT_TRUE(contains(m, "你")) << m;
  EXPECT_TRUE(contains(m, "pinyin")) << m;
}

TEST_F(EspeakTtsTest, KanjiToJapaneseVoiceIsRefused) {
  const std::string m = message_of<std::invalid_argument>([] { tts().speak("にほん 日本", "ja"); });
  EXPECT_TRUE(contains(m, "日")) << m;
  EXPECT_TRUE(contains(m, "kana")) << m;
}

TEST_F(EspeakTtsTest, MalformedUtf8IsRefused) {
  const std::string m = message_of<std::invalid_argument>([] { tts().speak("ab\xE4\xBD", "yue"); });
  EXPECT_TRUE(contains(m, "UTF-8")) << m;
  EXPECT_TRUE(contains(m, "byte 2")) << m;
  // An overlong encoding of '/' is malformed too.
  EXPECT_THROW(tts().speak("a\xC0\xAF", "en-us"), std::invalid_argument);
}

// A build without espeak-ng still declares the engine, which refuses with one line saying why.
TEST(EspeakTtsAbsent, RefusesWithOneLineSayingSpeechWasNotBuilt) {
  if (EspeakTts::built())
    GTEST_SKIP() << "speech is built; this checks the build without it (GPUJ2K_PERFORMER_SPEECH=OFF)";
  const std::string m = message_of<std::runtime_error>([] { EspeakTts().speak("hello", "en-us"); });
  EXPECT_TRUE(contains(m, "speech was not built")) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

// ---------------------------------------------------------------------------------------------
// Mapping files.

TEST(EspeakVisemes, ShippedFilesLoadForEveryLanguage) {
  for (const std::string voice : {"yue", "cmn-latn-pinyin", "ja", "en-us"}) {  // EspeakTts' languages()
    const EspeakVisemeMap& map = mapping(voice);
    EXPECT_EQ(map.voice, voice);
    EXPECT_FALSE(map.entries.empty()) << voice;
    // Pauses are the closed face in every voice.
    const auto* pause = performer::find_espeak_visemes(map, "_");
    ASSERT_NE(pause, nullptr) << voice;
    EXPECT_EQ(pause->visemes, std::vector<int>{0}) << voice;
  }
}

TEST(EspeakVisemes, UnmappedPhonemeIsNamed) {
  test_support::ScratchDir dir("performer_speech");
  // A hand-made Cantonese mapping that lacks "ei".
  const fs::path file = dir / "yue.tsv";
  write_text(file, "n yue n onset\nh yue h onset\nou yue o nucleus u coda\n_| yue closed any\n_: - 0\n_ - 0\n");
  const EspeakVisemeMap map = performer::load_espeak_visemes(file, library());
  // The phonemes espeak-ng reports for 你好 (EspeakTtsTest.CantoneseNeiHouIsNEiHOu), written out so
  // that the mapping is tested in builds without speech too.
  const std::vector<TimedPhoneme> phonemes = {{"n", 0.0, 0.1}, {"ei", 0.1, 0.1}, {"h", 0.2, 0.1}, {"ou", 0.3, 0.1}};
  try {
    performer::speech_visemes(phonemes, map);
    FAIL() << "no exception";
  } catch (const UnmappedSymbolError& e) {
    EXPECT_EQ(e.symbol(), "ei");
    EXPECT_EQ(e.language(), "yue");
    EXPECT_TRUE(contains(e.what(), "'ei'")) << e.what();
    EXPECT_TRUE(contains(e.what(), file.string())) << e.what();
  }
}

struct BadMapping {
  std::string text;
  int line;
  std::string says;
};

TEST(EspeakVisemes, MalformedFilesReportFileAndLine) {
  const std::vector<BadMapping> cases = {
      {"# header\nn yue n onset\nei yue\n", 3, "expected"},
      {"n yue n\n", 1, "has no role"},
      {"n yue n start\n", 1, "unknown role 'start'"},
      {"x fr a nucleus\n", 1, "no viseme table for language 'fr'"},
      {"\nq yue q onset\n", 2, "'q' as onset is not mapped"},
      {"u yue u any\n", 1, "roles disagree"},
      {"_ - 0\n_ - 1\n", 2, "already mapped on line 1"},
      {"x - 99\n", 1, "viseme ID '99'"},
      {"x - -1\n", 1, "viseme ID '-1'"},
      {"x - # a comment, no IDs\n", 1, "expected"},
  };
  for (const BadMapping& c : cases) {
    try {
      performer::parse_espeak_visemes(c.text, "bad.tsv", "yue", library());
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const VisemeDataError& e) {
      EXPECT_EQ(e.line(), c.line) << e.what();
      EXPECT_TRUE(contains(e.what(), "bad.tsv:" + std::to_string(c.line) + ": ")) << e.what();
      EXPECT_TRUE(contains(e.what(), c.says)) << e.what() << " (wanted: " << c.says << ")";
    }
  }
}

TEST(EspeakVisemes, CommentsStartOnlyAtAFieldStart) {
  // '#' inside a mnemonic ("t#", espeak-ng's flapped t) is part of it; "# ..." after the fields is
  // a comment. Direct IDs and several targets per line.
  const EspeakVisemeMap map = performer::parse_espeak_visemes(
      "\xEF\xBB\xBF# comment\r\nt#\ten\tt\tany  # the flap\r\nA@ en ɑː any ɹ any\r\nth - 12 12\r\n", "ok.tsv", "en-us",
      library());
  ASSERT_EQ(map.entries.size(), 3u);
  EXPECT_EQ(map.entries[0].mnemonic, "t#");
  EXPECT_EQ(map.entries[0].visemes, std::vector<int>{library().viseme_for("en", "t")});
  EXPECT_EQ(map.entries[0].line, 2);
  EXPECT_EQ(map.entries[1].visemes,
            (std::vector<int>{library().viseme_for("en", "ɑː"), library().viseme_for("en", "ɹ")}));
  EXPECT_EQ(map.entries[2].visemes, (std::vector<int>{12, 12}));
}

TEST(EspeakVisemes, MissingFileIsReported) {
  const std::string m = message_of<VisemeDataError>([] { performer::load_default_espeak_visemes("xx", library()); });
  EXPECT_TRUE(contains(m, "xx.tsv")) << m;
}

// ---------------------------------------------------------------------------------------------
// The timeline from engine marks.

TEST(PhonemesFromMarks, SortsClampsAndFillsToTheEnd) {
  const std::vector<PhonemeMark> marks = {{"b", 0.2}, {"a", 0.0}, {"c", 0.2}, {"late", 2.0}, {"early", -0.1}};
  const std::vector<TimedPhoneme> ph = performer::phonemes_from_marks(marks, 1.0);
  ASSERT_EQ(ph.size(), 5u);
  const std::vector<std::string> names = {"early", "a", "b", "c", "late"};
  for (std::size_t i = 0; i < ph.size(); ++i) EXPECT_EQ(ph[i].name, names[i]);
  EXPECT_DOUBLE_EQ(ph[0].start, 0.0);
  EXPECT_DOUBLE_EQ(ph[0].duration, 0.0);
  EXPECT_DOUBLE_EQ(ph[1].duration, 0.2);
  EXPECT_DOUBLE_EQ(ph[2].duration, 0.0);  // b and c start together: b takes no time
  EXPECT_DOUBLE_EQ(ph[3].end(), 1.0);
  EXPECT_DOUBLE_EQ(ph[4].start, 1.0);  // past the audio: clamped to its end
  EXPECT_DOUBLE_EQ(ph[4].duration, 0.0);
  EXPECT_TRUE(performer::phonemes_from_marks({}, 1.0).empty());
  EXPECT_THROW(performer::phonemes_from_marks(marks, -1.0), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// WAV files.

TEST(Wav, RoundTripsAndReplacesAtomically) {
  test_support::ScratchDir dir("performer_speech");
  const fs::path file = dir / "a.wav";
  write_text(file, "old contents");
  const std::vector<std::int16_t> samples = {0, 1, -1, 32767, -32768, 1234};
  performer::write_wav(file, 16000, samples);
  const performer::WavAudio back = performer::read_wav(file);
  EXPECT_EQ(back.sample_rate, 16000);
  EXPECT_EQ(back.samples, samples);
  EXPECT_EQ(fs::file_size(file), 44u + 2 * samples.size());
  // Nothing but the WAV is left in the folder: the temporary was renamed, not copied.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
  performer::write_wav(file, 8000, {});
  EXPECT_TRUE(performer::read_wav(file).samples.empty());
}

TEST(Wav, FailedWriteLeavesNothingBehind) {
  test_support::ScratchDir dir("performer_speech");
  // The target is a non-empty folder, so the final rename fails after the data was written.
  const fs::path target = dir / "taken.wav";
  fs::create_directory(target);
  write_text(target / "keep", "x");
  const std::string m =
      message_of<std::runtime_error>([&] { performer::write_wav(target, 22050, std::vector<std::int16_t>(100)); });
  EXPECT_TRUE(contains(m, target.string())) << m;
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
  // A folder that does not exist: nothing to create the temporary in.
  EXPECT_THROW(performer::write_wav(dir / "no" / "such.wav", 22050, {}), std::runtime_error);
  EXPECT_THROW(performer::write_wav(dir / "x.wav", 0, {}), std::invalid_argument);
}

TEST(Wav, ReaderRejectsWhatIsNotOneChannelOf16BitPcm) {
  test_support::ScratchDir dir("performer_speech");
  const fs::path file = dir / "a.wav";
  performer::write_wav(file, 22050, std::vector<std::int16_t>(10, 7));
  std::ifstream in(file, std::ios::binary);
  const std::string good{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  auto corrupt = [&](std::size_t at, char value) {
    std::string bytes = good;
    bytes[at] = value;
    return bytes;
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"not a wav at all", "not a RIFF/WAVE"},
      {good.substr(0, good.size() - 2), "RIFF header says"},
      {corrupt(22, 2), "not 16-bit mono PCM"},  // two channels
      {corrupt(34, 8), "not 16-bit mono PCM"},  // 8 bits
      {corrupt(32, 4), "block align"},
      {corrupt(40, 30), "runs past the end"},  // data size larger than the file
  };
  for (const auto& [bytes, says] : cases) {
    write_text(file, bytes);
    const std::string m = message_of<std::runtime_error>([&] { performer::read_wav(file); });
    EXPECT_TRUE(contains(m, file.string() + ": ")) << m;
    EXPECT_TRUE(contains(m, says)) << m << " (wanted: " << says << ")";
  }
  EXPECT_THROW(performer::read_wav(dir / "missing.wav"), std::runtime_error);
}

}  // namespace
