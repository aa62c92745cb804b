#include "espeak_engine.h"

#include <espeak-ng/espeak_ng.h>

#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string_view>

namespace performer::detail {

namespace {

// Everything below is guarded by session_mutex: espeak-ng is not re-entrant.
std::mutex session_mutex;
bool started = false;
std::string current_voice;
// Where the callback writes, set only for the duration of one synthesis. espeak-ng's callback has
// no context argument of its own (events carry user_data, but an audio block may come with none).
EspeakAudio* collecting = nullptr;
std::exception_ptr callback_error;

std::string status_message(espeak_ng_STATUS status) {
  char buffer[256] = {};
  espeak_ng_GetStatusCodeMessage(status, buffer, sizeof buffer);
  return buffer;
}

// id.string is zero-terminated unless the name needs all 8 bytes (speak_lib.h).
std::string phoneme_name(const espeak_EVENT& event) {
  return std::string(event.id.string, strnlen(event.id.string, sizeof event.id.string));
}

bool is_language_switch(std::string_view name) { return name.size() > 2 && name.front() == '(' && name.back() == ')'; }

void collect(EspeakAudio& out, const short* wav, int count, const espeak_EVENT* events) {
  if (wav && count > 0) out.samples.insert(out.samples.end(), wav, wav + count);
  for (const espeak_EVENT* e = events; e && e->type != espeakEVENT_LIST_TERMINATED; ++e) {
    if (e->type != espeakEVENT_PHONEME) continue;
    std::string name = phoneme_name(*e);
    if (is_language_switch(name)) continue;
    // audio_position is in milliseconds from the start of this synthesis.
    out.marks.push_back({std::move(name), e->audio_position / 1000.0});
  }
}

// espeak-ng's synthesis callback: returning 1 stops synthesis. Exceptions must not cross
// espeak-ng's C frames, so they are kept and rethrown once it returns.
int on_synth(short* wav, int count, espeak_EVENT* events) {
  if (!collecting) return 1;
  try {
    collect(*collecting, wav, count, events);
    return 0;
  } catch (...) {
    callback_error = std::current_exception();
    return 1;
  }
}

void start_locked() {
  if (started) return;
  espeak_ng_InitializePath(nullptr);
  espeak_ng_ERROR_CONTEXT context = nullptr;
  const espeak_ng_STATUS status = espeak_ng_Initialize(&context);
  espeak_ng_ClearErrorContext(&context);
  if (status != ENS_OK)
    throw std::runtime_error("espeak-ng: cannot load its data (" + status_message(status) +
                             "); is espeak-ng-data installed, or $ESPEAK_DATA_PATH right?");
  // The espeak_ng_* API has no switch for phoneme events; espeak_Initialize's option is the only
  // one. It repeats the initialisation just checked (so it cannot fail now, and prints nothing)
  // and calls espeak_ng_InitializeOutput(ENOUTPUT_MODE_SYNCHRONOUS): synthesis runs in the calling
  // thread and hands its audio to the callback, with no sound device opened.
  espeak_Initialize(AUDIO_OUTPUT_SYNCHRONOUS, 0, nullptr, espeakINITIALIZE_PHONEME_EVENTS | espeakINITIALIZE_DONT_EXIT);
  espeak_SetSynthCallback(&on_synth);
  started = true;
}

void select_voice_locked(const std::string& voice) {
  // Loading a voice reads its dictionary from disk: skip it when the voice is already current.
  if (voice == current_voice) return;
  const espeak_ng_STATUS status = espeak_ng_SetVoiceByName(voice.c_str());
  if (status != ENS_OK) {
    current_voice.clear();
    throw std::invalid_argument("espeak-ng has no voice '" + voice + "' (" + status_message(status) + ")");
  }
  current_voice = voice;
}

// Clears the callback's target however synthesis ends, so no late callback writes into a dead object.
class CollectInto {
 public:
  explicit CollectInto(EspeakAudio& out) {
    collecting = &out;
    callback_error = nullptr;
  }
  ~CollectInto() { collecting = nullptr; }
  CollectInto(const CollectInto&) = delete;
  CollectInto& operator=(const CollectInto&) = delete;
};

}  // namespace

void espeak_start() {
  const std::lock_guard lock(session_mutex);
  start_locked();
}

EspeakAudio espeak_synthesize(const std::string& voice, const std::string& text) {
  const std::lock_guard lock(session_mutex);
  start_locked();
  select_voice_locked(voice);
  EspeakAudio out;
  out.sample_rate = espeak_ng_GetSampleRate();
  {
    const CollectInto target(out);
    // Plain UTF-8 text: no SSML and no [[phoneme]] input, which would let text bypass the voice's
    // reading rules. The size argument is unused in synchronous mode; it is the buffer size.
    espeak_ng_STATUS status =
        espeak_ng_Synthesize(text.c_str(), text.size() + 1, 0, POS_CHARACTER, 0, espeakCHARS_UTF8, nullptr, nullptr);
    if (status == ENS_OK) status = espeak_ng_Synchronize();
    if (callback_error) std::rethrow_exception(callback_error);
    if (status != ENS_OK) throw std::runtime_error("espeak-ng: synthesis failed (" + status_message(status) + ")");
  }
  return out;
}

}  // namespace performer::detail
