// performer: the virtual performer from the command line.
//
//   performer info --bvh FILE                                  what a motion capture file holds
//   performer visemes --lang yue --text "你好" -o weights.csv   lip-sync weights per frame (+ --wav)
//   performer face --weights weights.csv -o frames/            the deformed head per frame
//   performer pose --bvh walk.bvh --frames 0:99 [--text ... --lang ...] -o frames/   the whole performer
//   performer render --bvh walk.bvh [--text ... --lang ...] [--effects env,hair,snow,toon] [--gltf avatar.glb] -o
//   out.mp4
//                                                              the rendered performer, as video with its speech
//   performer avatar --bvh walk.bvh -o avatar.glb              the generated performer as a glTF avatar
//
// Every failure is one line on stderr starting "performer: " and a non-zero exit: 2 for a command
// line that does not parse, 1 for anything that goes wrong running it.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include "base/one_line.h"
#include "avatar.h"
#include "face.h"
#include "info.h"
#include "pose.h"
#include "render.h"
#include "performer/bvh.h"
#include "performer/viseme_library.h"
#include "performer/weights_input.h"
#include "visemes.h"

namespace {

// The lip-sync options `visemes` takes.
void add_lip_sync_options(CLI::App* app, performer::cli::LipSyncSource& s) {
  app->add_option("--text", s.text,
                  "text for espeak-ng to speak (yue: hanzi; cmn-latn-pinyin: pinyin with tone digits; ja: kana)");
  app->add_option("--lang", s.language, "language of --text: yue, cmn-latn-pinyin, ja, en-us");
  app->add_option("--keyframes", s.keyframes,
                  "timing from a keyframe file instead: start duration symbol language per line");
  app->add_option("--rhubarb", s.rhubarb, "timing from Rhubarb Lip Sync output instead (TSV or JSON)");
  app->add_option("--wav", s.wav, "with --text: write the speech as 16-bit mono WAV");
  app->add_option("--fps", s.fps, "frames per second of the weight track (default 30)");
  app->add_option("--expression", s.expression, "a constant expression: smile, worry, surprise, anger");
  app->add_option("--expression-weight", s.expression_weight, "its weight (default 0.5)");
  app->add_option("--expressions", s.expressions, "expression keyframes instead: time expression weight per line");
  app->add_option("--curve", s.curve,
                  "viseme weight curve: linear (figure 3.8, default) or exponential (equation 3.8)");
  app->add_flag("!--no-blink", s.blink, "no eye blinks");
  app->add_option("--seed", s.seed, "seed of the blink generator (default 1)");
}

// "A:B" (inclusive frame indices) into first and last.
void parse_frame_range(const std::string& text, int& first, int& last) {
  const std::size_t colon = text.find(':');
  std::size_t used_first = 0, used_last = 0;
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    first = std::stoi(text.substr(0, colon), &used_first);
    last = std::stoi(text.substr(colon + 1), &used_last);
  } catch (const std::exception&) {
    throw std::invalid_argument("--frames must be A:B (first and last frame, from 0), not \"" + text + "\"");
  }
  if (used_first != colon || used_last != text.size() - colon - 1 || first < 0 || last < first)
    throw std::invalid_argument("--frames must be A:B with 0 <= A <= B, not \"" + text + "\"");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "performer: a virtual performer (thesis chapter 3): lip sync from text, a deformation-vector face, motion "
      "capture\n\n"
      "Examples:\n"
      "  performer info --bvh walk.bvh\n"
      "  performer visemes --lang yue --text \"你好\" --fps 30 -o weights.csv --wav hello.wav\n"
      "  performer visemes --lang en-us --text \"Hello there\" --expression smile -o weights.json\n"
      "  performer face --weights weights.csv -o frames/ --format obj\n"
      "  performer pose --bvh 131_01.bvh --frames 0:119 --lang en-us --text \"Hello\" -o frames/\n"
      "  performer render --bvh 131_01.bvh --lang en-us --text \"Hello\" --effects env,hair -o hello.mp4\n"
      "  performer avatar --bvh 131_01.bvh -o avatar.glb\n"
      "  performer render --bvh 131_01.bvh --gltf avatar.glb --lang en-us --text \"Hello\" -o avatar.mp4\n"};
  app.require_subcommand(1);

  std::string bvh_path;
  CLI::App* info = app.add_subcommand("info", "print a BVH file's joints, channels, frame count and duration");
  info->add_option("--bvh", bvh_path, "BVH motion capture file")->required();

  performer::cli::LipSyncSource lip_sync;
  std::filesystem::path weights_out;
  CLI::App* visemes =
      app.add_subcommand("visemes", "lip-sync blending weights per frame, as CSV or JSON (by -o's extension)");
  add_lip_sync_options(visemes, lip_sync);
  visemes->add_option("-o,--output", weights_out, "weights file: .csv or .json")->required();

  std::filesystem::path weights_in;
  performer::cli::FaceCommand face_command;
  CLI::App* face =
      app.add_subcommand("face", "the deformed head for every frame of a weight track, as PLY or OBJ files");
  face->add_option("--weights", weights_in, "weight track CSV (performer visemes)")->required();
  face->add_option("-o,--output", face_command.out_dir, "folder for frame_00000.ply, ...")->required();
  face->add_option("--format", face_command.format, "ply (default) or obj");
  face->add_option("--gltf", face_command.gltf,
                   "a glTF 2.0 avatar whose morph targets have Oculus or ARKit names (default: the procedural head)");
  face->add_option("--threads", face_command.threads, "threads (default: all)");

  performer::cli::LipSyncSource pose_lip_sync;
  performer::cli::PoseCommand pose_command;
  std::string frame_range;
  std::filesystem::path pose_weights;
  CLI::App* pose = app.add_subcommand("pose",
                                      "the whole performer (generated body, procedural head) per motion capture frame, "
                                      "face driven by speech or a weight track (equation 3.20), as PLY or OBJ files");
  pose->add_option("--bvh", pose_command.bvh, "BVH motion capture file")->required();
  pose->add_option("--frames", frame_range, "first and last frame, A:B, from 0")->required();
  pose->add_option("-o,--output", pose_command.out_dir, "folder for frame_NNNNN.ply (NNNNN: the BVH frame)")
      ->required();
  pose->add_option("--format", pose_command.format, "ply (default) or obj");
  pose->add_option("--threads", pose_command.threads, "threads (default: all)");
  pose->add_option("--weights", pose_weights,
                   "face weights from a CSV (performer visemes) instead of lip-sync options");
  add_lip_sync_options(pose, pose_lip_sync);

  performer::cli::LipSyncSource render_lip_sync;
  performer::cli::RenderCommand render_command;
  std::string render_frames, render_size;
  std::filesystem::path render_weights;
  CLI::App* render = app.add_subcommand("render",
                                        "the performer rendered on the GPU (equation 3.20 in a vertex shader, section "
                                        "3.7's effects), as an MP4 with the speech or as PNG frames");
  render->add_option("--bvh", render_command.bvh, "BVH motion capture file")->required();
  render->add_option("--frames", render_frames, "first and last BVH frame, A:B, from 0 (default: the whole clip)");
  render->add_option("-o,--output", render_command.out, "an .mp4 file, or a folder for frame_00000.png, ...")
      ->required();
  render->add_option("--effects", render_command.effects,
                     "any of env, hair, snow, toon, comma-separated (default none)");
  render->add_option("--size", render_size, "frame size WxH (default 640x480; even for MP4)");
  render->add_option("--gl", render_command.gl_platform,
                     "GL platform: auto, egl-device, egl-surfaceless, egl-default, osmesa");
  render->add_option("--cubemap", render_command.cubemap_dir,
                     "folder with posx/negx/posy/negy/posz/negz for env (default ../shared/assets/cubemap)");
  render->add_option("--threads", render_command.threads, "threads for building the character (default: all)");
  render->add_option("--gltf", render_command.gltf,
                     "a glTF 2.0 avatar (.glb/.gltf) instead of the generated performer: a skinned mesh whose joints "
                     "follow the clip's by name and whose morph targets (Oculus or ARKit names) are the face, or a "
                     "face alone, put on the generated body");
  render->add_option("--weights", render_weights,
                     "face weights from a CSV (performer visemes) instead of lip-sync options");
  add_lip_sync_options(render, render_lip_sync);

  performer::cli::AvatarCommand avatar_command;
  CLI::App* avatar = app.add_subcommand("avatar",
                                        "the generated performer (body grown around the BVH's skeleton, procedural "
                                        "head) as a glTF 2.0 avatar in metres: skinned, with the face's targets "
                                        "as morph targets");
  avatar->add_option("--bvh", avatar_command.bvh, "BVH motion capture file (its skeleton)")->required();
  avatar->add_option("-o,--output", avatar_command.out, "a .glb or .gltf file")->required();
  avatar->add_option("--threads", avatar_command.threads, "threads (default: all)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "performer: %s\n", base::one_line(e.what()).c_str());
    return 2;
  }

  try {
    if (info->parsed()) {
      const performer::Bvh bvh = performer::read_bvh(bvh_path);
      performer::cli::print_info(bvh, bvh_path, stdout);
    } else if (visemes->parsed()) {
      const auto library = performer::VisemeLibrary::load_default();
      const performer::WeightTrack track = performer::cli::lip_sync_track(lip_sync, library);
      performer::cli::write_track(track, weights_out);
      std::fprintf(stderr, "visemes: %zu frames at %g fps, %zu channels written to %s\n", track.frame_count(),
                   track.fps, track.channel_count(), weights_out.string().c_str());
    } else if (face->parsed()) {
      const auto library = performer::VisemeLibrary::load_default();
      if (weights_in.extension() == ".json")
        throw std::invalid_argument(
            weights_in.string() + ": --weights reads the CSV that performer visemes writes (JSON is for other tools)");
      const performer::WeightTrack track = performer::read_weights_csv(weights_in, library.visemes());
      const performer::FaceModel model = performer::cli::load_face(face_command.gltf, library.visemes(), stderr);
      performer::cli::run_face(face_command, track, model, stderr);
    } else if (pose->parsed()) {
      parse_frame_range(frame_range, pose_command.first_frame, pose_command.last_frame);
      const bool lip_sync =
          !pose_lip_sync.text.empty() || !pose_lip_sync.keyframes.empty() || !pose_lip_sync.rhubarb.empty();
      if (lip_sync && !pose_weights.empty())
        throw std::invalid_argument("give --weights or lip-sync options, not both");
      performer::WeightTrack track;
      if (lip_sync || !pose_weights.empty()) {
        const auto library = performer::VisemeLibrary::load_default();
        track = lip_sync ? performer::cli::lip_sync_track(pose_lip_sync, library)
                         : performer::read_weights_csv(pose_weights, library.visemes());
        pose_command.weights = &track;
      }
      performer::cli::run_pose(pose_command, stderr);
    } else if (render->parsed()) {
      if (!render_frames.empty())
        parse_frame_range(render_frames, render_command.first_frame, render_command.last_frame);
      if (!render_size.empty()) {
        const std::size_t x = render_size.find('x');
        try {
          if (x == std::string::npos) throw std::invalid_argument("no x");
          std::size_t used_w = 0, used_h = 0;
          render_command.width = std::stoi(render_size.substr(0, x), &used_w);
          render_command.height = std::stoi(render_size.substr(x + 1), &used_h);
          if (used_w != x || used_h != render_size.size() - x - 1) throw std::invalid_argument("trailing text");
        } catch (const std::exception&) {
          throw std::invalid_argument("--size must be WxH, for example 1280x720, not \"" + render_size + "\"");
        }
      }
      if (render_command.cubemap_dir.empty()) render_command.cubemap_dir = "../shared/assets/cubemap";
      render_command.fps = static_cast<int>(std::lround(render_lip_sync.fps));  // --fps: the video's and the track's
      const bool lip_sync =
          !render_lip_sync.text.empty() || !render_lip_sync.keyframes.empty() || !render_lip_sync.rhubarb.empty();
      if (lip_sync && !render_weights.empty())
        throw std::invalid_argument("give --weights or lip-sync options, not both");
      performer::WeightTrack track;
      performer::Speech speech;
      if (lip_sync || !render_weights.empty()) {
        const auto library = performer::VisemeLibrary::load_default();
        track = lip_sync ? performer::cli::lip_sync_track(render_lip_sync, library, &speech)
                         : performer::read_weights_csv(render_weights, library.visemes());
        render_command.weights = &track;
        if (!speech.samples.empty()) render_command.speech = &speech;
      }
      performer::cli::run_render(render_command, stderr);
    } else if (avatar->parsed()) {
      performer::cli::run_avatar(avatar_command, stderr);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "performer: %s\n", base::one_line(e.what()).c_str());
    return 1;
  }
  return 0;
}
