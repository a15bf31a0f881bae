#include "app/demo/scenario_run.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "app/demo/demo_app.h"
#include "app/demo/headless.h"
#include "app/demo/world_session.h"
#include "app/render/gl_context.h"
#include "app/render/image.h"

namespace prep::demo {

bool ffmpeg_available() { return std::system("command -v ffmpeg > /dev/null 2>&1") == 0; }

render::Image downscale(const render::Image& image, int factor) {
  if (factor <= 1) return image;
  render::Image out(image.width / factor, image.height / factor);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      int sum[4] = {0, 0, 0, 0};
      for (int dy = 0; dy < factor; ++dy)
        for (int dx = 0; dx < factor; ++dx) {
          const std::uint8_t* p = image.pixel(x * factor + dx, y * factor + dy);
          for (int c = 0; c < 4; ++c) sum[c] += p[c];
        }
      std::uint8_t* q = out.pixel(x, y);
      for (int c = 0; c < 4; ++c) q[c] = static_cast<std::uint8_t>(sum[c] / (factor * factor));
    }
  return out;
}

namespace {

constexpr int kScreenshotLeadFrames = 2 * kVideoFps;

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Raw RGBA frames piped into ffmpeg, which writes the MP4 to a temporary name beside the target; the
// finished file is renamed over the target (atomic, like every file prep writes).
class VideoWriter {
 public:
  VideoWriter(const std::string& path, int width, int height) : path_(path) {
    partial_ = path + ".partial-" + std::to_string(::getpid()) + ".mp4";
    const std::string command = "ffmpeg -loglevel error -y -f rawvideo -pix_fmt rgba -s " + std::to_string(width) + "x" +
                                std::to_string(height) + " -r " + std::to_string(kVideoFps) +
                                " -i - -an -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' -pix_fmt yuv420p -f mp4 " +
                                shell_quote(partial_);
    pipe_ = ::popen(command.c_str(), "w");
    if (!pipe_) throw std::runtime_error(path + ": cannot start ffmpeg");
  }
  ~VideoWriter() {
    if (pipe_) ::pclose(pipe_);
    std::error_code ec;
    std::filesystem::remove(partial_, ec);
  }
  void add(const render::Image& frame) {
    if (std::fwrite(frame.rgba.data(), 1, frame.rgba.size(), pipe_) != frame.rgba.size())
      throw std::runtime_error(path_ + ": ffmpeg stopped reading frames");
  }
  void finish() {
    const int status = ::pclose(pipe_);
    pipe_ = nullptr;
    if (status != 0) throw std::runtime_error(path_ + ": ffmpeg failed (exit status " + std::to_string(status) + ")");
    std::filesystem::rename(partial_, path_);
  }

 private:
  std::string path_, partial_;
  FILE* pipe_ = nullptr;
};

// Progress of loading and training on stderr: a line when the phase changes and every 2 s.
std::function<void(const std::string&, float)> progress_printer() {
  auto last = std::make_shared<std::chrono::steady_clock::time_point>();
  auto last_status = std::make_shared<std::string>();
  return [last, last_status](const std::string& status, float progress) {
    const auto now = std::chrono::steady_clock::now();
    const std::string kind = status.substr(0, status.find(':'));
    if (kind == *last_status && now - *last < std::chrono::seconds(2)) return;
    *last = now;
    *last_status = kind;
    std::fprintf(stderr, "prep-demo: %s (%.0f%%)\n", status.c_str(), 100.0 * progress);
  };
}

}  // namespace

int run_frames(WorldSession& session, float seconds, bool until_goal) {
  const int most = std::max(1, static_cast<int>(std::lround(seconds * kVideoFps)));
  if (!until_goal || !session.world()) return most;
  const int tail = static_cast<int>(std::lround(kGoalTail * kVideoFps));
  int done_since = -1;  // the frame from which the course has been done, or -1
  for (int f = 0; f < most; ++f) {
    session.advance(1.0 / kVideoFps);
    if (!session.world()->done()) {
      done_since = -1;
      continue;
    }
    if (done_since < 0) done_since = f;
    if (f - done_since >= tail) return f + 1;
  }
  return most;
}

std::vector<int> strip_frames(int frames) {
  const int last = std::max(frames, 1) - 1;
  const int first = std::min(kVideoFps, last / kStripTiles);
  std::vector<int> out;
  for (int k = 0; k < kStripTiles; ++k) out.push_back(first + (last - first) * k / (kStripTiles - 1));
  return out;
}

ScenarioRunResult run_scenario_headless(const ScenarioRunOptions& o) {
  if (!(o.seconds > 0.0f)) throw std::invalid_argument("--seconds must be positive");
  SessionOptions so;
  so.cache_dir = o.cache_dir;
  so.background = false;
  so.on_progress = progress_printer();
  WorldSession session(so);
  session.open(o.scenario, o.params.empty() ? std::nullopt : std::optional<Params>(load_params(o.params)));

  if (o.bench_frames > 0) {
    render::OsMesaContext context(o.width, o.height);
    DemoApp app(context, session, nullptr, o.render);
    app.view.show_panels = o.panels;
    app.view.show_clearance = o.clearance;
    app.motion_folder = o.motion_folder;
    const BenchResult r = bench_app(app, context, o.bench_frames);
    std::cout << "prep-demo: scenario " << session.scenario().name << ", " << bench_report(r, o.width, o.height, o.panels, o.bench_frames)
              << "\n  engine per frame (ms): controller " << app.engine_timings.control.value() << "  motion graph "
              << app.engine_timings.motion.value() << "  synthesis " << app.engine_timings.synthesis.value()
              << "  balance " << app.engine_timings.balance.value() << "  total " << app.engine_timings.total.value()
              << "  (" << app.engine_timings.ticks.value() << " ticks per frame)\n";
    return {};
  }
  ScenarioRunResult result;
  result.frames = run_frames(session, o.seconds, o.until_goal);
  if (o.until_goal) session.restart();  // the run to draw: the same world from its start, to that frame

  std::string video = o.video, strip = o.strip;
  if (!video.empty() && !ffmpeg_available()) {
    std::filesystem::path fallback(video);
    fallback.replace_extension(".png");
    if (strip.empty()) strip = fallback.string();
    std::cerr << "prep-demo: ffmpeg is not installed: no video; a strip of frames goes to " << strip << " instead\n";
    video.clear();
  }
  const bool drawing = !o.screenshot.empty() || !o.frames_dir.empty() || !video.empty() || !strip.empty();
  std::unique_ptr<render::OsMesaContext> context;
  std::unique_ptr<DemoApp> app;
  std::unique_ptr<VideoWriter> writer;
  if (drawing) {
    context = std::make_unique<render::OsMesaContext>(o.width, o.height);
    app = std::make_unique<DemoApp>(*context, session, nullptr, o.render);
    app->view.show_panels = o.panels;
    app->view.show_clearance = o.clearance;
    app->motion_folder = o.motion_folder;
    if (!o.frames_dir.empty()) std::filesystem::create_directories(o.frames_dir);
    if (!video.empty()) writer = std::make_unique<VideoWriter>(video, o.width, o.height);
  }

  const int frames = result.frames;
  const float dt = 1.0f / kVideoFps;
  if (o.until_goal && !o.json) {
    char line[160];
    if (frames < std::lround(o.seconds * kVideoFps))
      std::snprintf(line, sizeof line, "the course is done (goal reached, nothing playing): the run ends at %.1f s", frames * dt);
    else
      std::snprintf(line, sizeof line, "the course is not done within --seconds %.1f: the run ends there", o.seconds);
    std::cout << "prep-demo: " << line << "\n";
  }
  const std::vector<int> strip_at = strip.empty() ? std::vector<int>() : strip_frames(frames);
  const int strip_factor = 3;
  render::Image strip_image;
  if (!strip.empty()) strip_image = render::Image(kStripColumns * (o.width / strip_factor), kStripRows * (o.height / strip_factor));
  int tile = 0, written = 0;
  for (int f = 0; f < frames; ++f) {
    const bool strip_frame = tile < static_cast<int>(strip_at.size()) && strip_at[static_cast<size_t>(tile)] == f;
    // The screenshot's last frames are drawn (two seconds of them: the panels' timings settle).
    const bool screenshot_frame = !o.screenshot.empty() && f >= frames - kScreenshotLeadFrames;
    const bool every_frame = !o.frames_dir.empty() || writer;
    if (!app || !(every_frame || strip_frame || screenshot_frame)) {
      if (app) app->skip_frame(dt);
      else session.advance(dt);
      continue;
    }
    if (strip_frame) {
      // Tiles are a third of the frame: no panels, a caption drawn three times as large as the panels' text.
      const bool panels = app->view.show_panels;
      app->view.show_panels = false;
      char caption[160];
      const World* w = session.world();
      const WorldCharacter& u = w->characters()[static_cast<size_t>(w->user())];
      std::snprintf(caption, sizeof caption, "t = %.1f s   alpha %.2f%s%s", w->time() + dt, u.alpha,
                    u.in_target ? "   " : "", u.in_target ? target_action_name(u.playing) : "");
      app->view.caption = caption;
      app->view.caption_scale = static_cast<float>(strip_factor);
      app->frame(dt);
      app->view.caption.clear();
      app->view.show_panels = panels;
      const render::Image small = downscale(context->read_pixels(), strip_factor);
      // Every tile of this frame (a run shorter than the strip shows a frame in several).
      for (; tile < static_cast<int>(strip_at.size()) && strip_at[static_cast<size_t>(tile)] == f; ++tile) {
        result.strip_times.push_back(w->time());
        const int x0 = (tile % kStripColumns) * small.width, y0 = (tile / kStripColumns) * small.height;
        for (int y = 0; y < small.height; ++y)
          for (int x = 0; x < small.width; ++x)
            for (int c = 0; c < 4; ++c) strip_image.pixel(x0 + x, y0 + y)[c] = small.pixel(x, y)[c];
      }
      if (!every_frame && !screenshot_frame) continue;
      app->frame(0.0f);  // the same instant again, as the other frames show it (panels, no caption)
    } else {
      app->frame(dt);
    }
    const render::Image image = context->read_pixels();
    if (!o.frames_dir.empty()) {
      char name[64];
      std::snprintf(name, sizeof name, "/frame_%05d.png", written);
      render::write_png(image, o.frames_dir + name);
    }
    if (writer) writer->add(image);
    ++written;
  }
  if (!o.screenshot.empty()) {
    render::write_png(context->read_pixels(), o.screenshot);
    if (!o.json) std::cout << "prep-demo: wrote " << o.screenshot << "\n";
  }
  if (writer) {
    writer->finish();
    if (!o.json) std::cout << "prep-demo: wrote " << video << " (" << written << " frames at " << kVideoFps << " frames/s)\n";
  }
  if (!strip.empty()) {
    render::write_png(strip_image, strip);
    if (!o.json) std::cout << "prep-demo: wrote " << strip << " (" << kStripTiles << " frames of the run)\n";
  }
  if (!o.frames_dir.empty() && !o.json) std::cout << "prep-demo: wrote " << written << " frames into " << o.frames_dir << "\n";
  const World& world = *session.world();
  result.seconds = world.time();
  result.frames_written = written;
  result.summary = summarize(world);
  if (o.json)
    std::cout << summary_json(result.summary, world) << "\n";
  else
    std::cout << summary_text(result.summary);
  return result;
}

}  // namespace prep::demo
