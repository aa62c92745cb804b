#include "visemes.h"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "base/atomic_file.h"
#include "performer/espeak_tts.h"
#include "performer/espeak_visemes.h"
#include "performer/phoneme_keyframes.h"
#include "performer/speech_visemes.h"
#include "performer/viseme_rhubarb.h"
#include "performer/wav.h"
#include "performer/weights_expression.h"
#include "performer/weights_output.h"

namespace performer::cli {

WeightTrack lip_sync_track(const LipSyncSource& source, const VisemeLibrary& library, Speech* speech_out) {
  const int sources = !source.text.empty() + !source.keyframes.empty() + !source.rhubarb.empty();
  if (sources != 1) throw std::invalid_argument("give exactly one of --text, --keyframes and --rhubarb");
  if (!source.wav.empty() && source.text.empty()) throw std::invalid_argument("--wav needs --text (speech to write)");

  std::vector<TimedViseme> visemes;
  double end = -1.0;  // up to the last viseme, or the end of the audio
  if (!source.text.empty()) {
    if (source.language.empty()) throw std::invalid_argument("--text needs --lang (yue, cmn-latn-pinyin, ja or en-us)");
    EspeakTts tts;
    const Speech speech = tts.speak(source.text, source.language);
    const EspeakVisemeMap map = load_default_espeak_visemes(source.language, library);
    visemes = speech_visemes(speech.phonemes, map);
    end = speech.duration();
    if (!source.wav.empty()) write_wav(source.wav, speech.sample_rate, speech.samples);
    if (speech_out) *speech_out = speech;
  } else if (!source.keyframes.empty()) {
    visemes = keyframes_to_visemes(read_phoneme_keyframes(source.keyframes), library, source.keyframes.string());
  } else {
    visemes = rhubarb_to_visemes(read_rhubarb(source.rhubarb), library);
  }

  std::vector<ExpressionKey> expressions;
  if (!source.expression.empty() && !source.expressions.empty())
    throw std::invalid_argument("give --expression or --expressions, not both");
  if (!source.expression.empty()) expressions = constant_expression(source.expression, source.expression_weight);
  if (!source.expressions.empty()) expressions = read_expression_keys(source.expressions);

  TrackOptions options;
  options.fps = source.fps;
  options.end = end;
  options.blink = source.blink;
  options.blink_params.seed = source.seed;
  if (source.curve == "exponential")
    options.weights.curve = WeightCurve::exponential;
  else if (source.curve != "linear")
    throw std::invalid_argument("--curve must be linear or exponential, not \"" + source.curve + "\"");
  return build_weight_track(visemes, library.visemes(), expressions, options);
}

void write_track(const WeightTrack& track, const std::filesystem::path& out) {
  std::ostringstream text;
  if (out.extension() == ".json")
    write_weights_json(text, track);
  else
    write_weights_csv(text, track);
  base::replace_file_atomically(out, text.str());
}

}  // namespace performer::cli
