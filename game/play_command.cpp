// `ballbox play`: the scene in a window in real time, drawn by the same renderer as `ballbox
// render` (its picture copied to the window), with clicks, right-button drags, keys, recording
// and replay.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "game/commands.h"
#include "game/interrupt.h"
#include "game/output_file.h"
#include "game/play_controller.h"
#include "game/play_view.h"
#include "game/scene_colors.h"
#include "game/screenshot.h"
#include "render/bitmap_text.h"
#include "render/renderer.h"
#include "render/window.h"

namespace game {

namespace {

constexpr const char* kScreenshotDir = "screenshots";
constexpr render::Color kBarColor{0x20, 0x23, 0x28};

Failure NoDisplay(const std::string& reason) {
  return RuntimeFailure("ballbox play needs a window, and there is no display (" + reason +
                        "); try ballbox render to write the frames as PNG files instead");
}

// A step count from the environment: the hooks tests and demos use (docs/play.md).
Expected<std::optional<std::int64_t>> StepFromEnvironment(const char* name) {
  const char* text = std::getenv(name);
  if (text == nullptr) return std::optional<std::int64_t>();
  const std::string value = text;
  std::int64_t step = 0;
  bool ok = !value.empty() && value.size() <= 15;
  for (const char c : value) {
    ok = ok && c >= '0' && c <= '9';
    if (ok) step = step * 10 + (c - '0');
  }
  if (!ok) {
    return BadInput(std::string(name) + ": expected a step number (a whole number >= 0), got \"" +
                    value + "\"");
  }
  return std::optional<std::int64_t>(step);
}

// Frames drawn per second, measured over half a second so the number can be read.
class FpsMeter {
 public:
  void Frame(std::chrono::steady_clock::time_point now) {
    if (frames_ == 0 && !started_) {
      start_ = now;
      started_ = true;
    }
    ++frames_;
    const double seconds = std::chrono::duration<double>(now - start_).count();
    if (seconds >= 0.5) {
      fps_ = frames_ / seconds;
      frames_ = 0;
      start_ = now;
    }
  }
  double Fps() const { return fps_; }

 private:
  bool started_ = false;
  int frames_ = 0;
  std::chrono::steady_clock::time_point start_;
  double fps_ = 0.0;
};

std::vector<render::FilledRect> StatusOverlay(const std::string& text, int framebuffer_width) {
  // Twice the font's cells on a window wide enough; the line stays small either way.
  return render::TextPanel(text, framebuffer_width >= 480 ? 2 : 1, render::kPanelBackdrop, render::kPanelText);
}

std::string Title(const PlayController& controller) {
  std::string title = "ballbox play: " + controller.GetSession().SceneDef().name;
  if (controller.Paused()) {
    title += " (paused at step " + std::to_string(controller.GetSession().StepIndex()) + ")";
  }
  return title;
}

void TakeScreenshot(render::Renderer& renderer, const PlayController& controller,
                    const SceneColors& colors) {
  // Drawn afresh from the current state, so the file shows exactly the step its name says.
  const Session& session = controller.GetSession();
  renderer.Draw(session.World(), colors.bodies, controller.Camera(), {}, colors.particles);
  render::Image image;
  renderer.ReadImage(image);
  Expected<std::string> path = SaveScreenshot(
      image, kScreenshotDir, ScreenshotStem(session.SceneDef().name, session.StepIndex()));
  if (path.HasValue()) {
    std::printf("play: screenshot at step %" PRId64 " -> %s\n", session.StepIndex(),
                path.Value().c_str());
  } else {
    std::fprintf(stderr, "play: no screenshot: %s\n", path.Error().message.c_str());
  }
  std::fflush(stdout);
}

std::string RecordingHeader(const PlayOptions& options, const PlayController& controller) {
  const Session& session = controller.GetSession();
  char line[200];
  std::snprintf(line, sizeof line, "# stopped at step %" PRId64 ", state-hash: %016" PRIx64 "\n",
                session.StepIndex(), session.World().StateHash());
  const std::string scene =
      options.run.scene_path ? *options.run.scene_path : std::string("(the built-in scene)");
  // The recording holds world points, which need no size; the size line says what the window
  // showed, and a pixel click added by hand below it maps at that size.
  return "# recorded by ballbox play: " + scene + "\n" + line +
         "# every event applied, live or scripted, as the world point it acted on\n" +
         SizeLine(session.ImageWidth(), session.ImageHeight());
}

constexpr int kClickButton = 0;  // left
constexpr int kGrabButton = 1;   // right

// The right button's drag: a grab where it goes down, the target following the cursor (also off
// the picture, and as a followed camera moves) while it is held, a release where it goes up.
class DragInput {
 public:
  void Press(PlayController& controller, engine::Vec2 p) {
    controller.Grab(p);
    held_ = true;
    target_ = p;
  }
  void Let(PlayController& controller) {
    if (!held_) return;  // pressed on a bar: nothing was grabbed
    controller.Release();
    held_ = false;
  }
  void Move(PlayController& controller, const render::PixelRect& picture, double x, double y) {
    cursor_x_ = x;
    cursor_y_ = y;
    cursor_known_ = true;
    Follow(controller, picture);
  }
  void Follow(PlayController& controller, const render::PixelRect& picture) {
    if (!held_ || !cursor_known_ || picture.width == 0) return;
    const engine::Vec2 p = PicturePointToWorld(controller.Camera(), picture, cursor_x_, cursor_y_);
    if (p == target_) return;  // a drag only when the target moves
    controller.Drag(p);
    target_ = p;
  }

 private:
  bool held_ = false;
  engine::Vec2 target_;
  bool cursor_known_ = false;
  double cursor_x_ = 0.0;
  double cursor_y_ = 0.0;
};

// The window loop. Returns when the user quits, the stop step is reached, or GL fails.
Status RunWindow(render::Window& window, render::Renderer& renderer, PlayController& controller,
                 const SceneColors& colors) {
  using Clock = std::chrono::steady_clock;
  Clock::time_point last = Clock::now();
  FpsMeter fps;
  std::string title;
  int framebuffer_width = 0;
  int framebuffer_height = 0;
  window.FramebufferSize(framebuffer_width, framebuffer_height);
  render::PixelRect picture = Letterbox(framebuffer_width, framebuffer_height, renderer.Width(),
                                        renderer.Height());
  const int image_width = controller.GetSession().ImageWidth();
  const int image_height = controller.GetSession().ImageHeight();
  DragInput drag;

  while (!Interrupted()) {
    // Nothing changes before the next step is due, so wait for it (or for input) rather than
    // redraw the same state; a paused game only waits for input.
    const bool idle = controller.Paused() || controller.Finished();
    bool quit = false;
    for (const render::WindowEvent& event :
         window.TakeEvents(idle ? 0.25 : controller.SecondsToNextStep())) {
      if (event.type == render::WindowEvent::Type::kClose) {
        quit = true;
      } else if (event.type == render::WindowEvent::Type::kMouseDown) {
        // Clicks on the letterbox bars are on no part of the picture and do nothing.
        const auto p = WindowPointToWorld(controller.Camera(), picture, event.x, event.y);
        if (!p) continue;
        if (event.button == kClickButton) controller.Click(*p);
        if (event.button == kGrabButton) drag.Press(controller, *p);
      } else if (event.type == render::WindowEvent::Type::kMouseUp) {
        if (event.button == kGrabButton) drag.Let(controller);
      } else if (event.type == render::WindowEvent::Type::kMouseMove) {
        drag.Move(controller, picture, event.x, event.y);
      } else if (event.key == "escape") {
        quit = true;
      } else if (event.key == ".") {
        controller.StepOnce();  // held down, it keeps stepping
      } else if (event.key == "backspace") {
        controller.Rewind();  // held down, it keeps going back
      } else if (event.repeat) {
        continue;  // the other keys act once per press
      } else if (event.key == "space") {
        controller.TogglePause();
      } else if (event.key == "r") {
        std::printf("play: restart at step %" PRId64 ": back to step 0, the recording starts over\n",
                    controller.GetSession().StepIndex());
        std::fflush(stdout);
        controller.Restart();
      } else if (event.key == "s") {
        TakeScreenshot(renderer, controller, colors);
      }
      if (quit) break;  // what follows Esc in the same batch is not acted on
    }
    if (quit) break;
    // A camera that follows a body moves the world under a cursor that holds still.
    drag.Follow(controller, picture);

    const Clock::time_point now = Clock::now();
    controller.Advance(std::chrono::duration<double>(now - last).count());
    last = now;
    if (controller.Finished()) break;
    // A broken-down state ends the session with its report; it is never drawn.
    if (Status fault = controller.GetSession().Fault()) return fault;

    window.FramebufferSize(framebuffer_width, framebuffer_height);
    picture = Letterbox(framebuffer_width, framebuffer_height, image_width, image_height);
    if (picture.width == 0) continue;  // minimised: nothing to draw into
    if (picture.width != renderer.Width() || picture.height != renderer.Height()) {
      // Drawn at the size it is shown, so it stays sharp; on failure the old size is scaled.
      std::string error;
      if (!renderer.Resize(picture.width, picture.height, error)) {
        std::fprintf(stderr, "play: %s\n", error.c_str());
      }
    }
    const Session& session = controller.GetSession();
    renderer.Draw(session.World(), colors.bodies, controller.Camera(), {}, colors.particles);
    const double time = static_cast<double>(session.StepIndex()) * session.World().Def().dt;
    const std::vector<render::FilledRect> overlay = StatusOverlay(
        StatusLine(session.StepIndex(), time, fps.Fps(), controller.Paused()), framebuffer_width);
    renderer.Present(framebuffer_width, framebuffer_height, picture, overlay, kBarColor);
    window.SwapBuffers();
    fps.Frame(Clock::now());
    if (std::string now_title = Title(controller); now_title != title) {
      window.SetTitle(now_title);
      title = std::move(now_title);
    }
  }
  return std::nullopt;
}

}  // namespace

Status RunPlay(const PlayOptions& options) {
  // Bad input is reported first (exit 2), as in every command, and before anything opens.
  Expected<RunInput> input = LoadRunInput(options.run);
  if (!input.HasValue()) return input.Error();
  Expected<std::optional<engine::BodyId>> follow = FollowedBody(
      input.Value().scene, options.view, options.run.scene_path.value_or("the default scene"));
  if (!follow.HasValue()) return follow.Error();
  Expected<std::optional<std::int64_t>> stop_at = StepFromEnvironment("BALLBOX_PLAY_STOP_AT");
  if (!stop_at.HasValue()) return stop_at.Error();
  Expected<std::optional<std::int64_t>> pause_at = StepFromEnvironment("BALLBOX_PLAY_PAUSE_AT");
  if (!pause_at.HasValue()) return pause_at.Error();

  if (!render::WindowSupportBuilt()) {
    return RuntimeFailure(
        "ballbox play is not available: this ballbox was built without GLFW (install "
        "libglfw3-dev and rebuild with -DBALLBOX_WITH_GLFW=ON); try ballbox render to write the "
        "frames as PNG files instead");
  }
  std::string reason;
  if (!render::DisplayConfigured(reason)) return NoDisplay(reason);

  // Opened before the window, so an unwritable path fails at once; it appears only on Commit.
  std::optional<AtomicOutputFile> record;
  if (options.record_path) {
    Expected<AtomicOutputFile> file = AtomicOutputFile::Open(*options.record_path);
    if (!file.HasValue()) return file.Error();
    record.emplace(std::move(file.Value()));
  }

  const int width = options.run.width;
  const int height = options.run.height;
  PlayController controller(std::move(input.Value().scene), std::move(input.Value().events),
                            width, height, PlayLimits{stop_at.Value(), pause_at.Value()},
                            kMaxFrameSeconds, FilmView{options.view.camera, follow.Value()});
  if (options.run.load_state_path) {
    if (Status refused = controller.LoadState(*options.run.load_state_path)) return refused;
  }
  std::string error;
  render::Window::Failure failure = render::Window::Failure::kNone;
  std::unique_ptr<render::Window> window =
      render::Window::Open(width, height, Title(controller), failure, error);
  if (!window) {
    return failure == render::Window::Failure::kNoDisplay ? NoDisplay(error)
                                                          : RuntimeFailure(error);
  }
  std::unique_ptr<render::Renderer> renderer =
      render::Renderer::Create(*window, width, height, error);
  if (!renderer) return RuntimeFailure(error);
  const SceneColors colors = ColorsOf(controller.GetSession().SceneDef());

  Status status;
  {
    // Ctrl-C in the terminal ends the run as Esc does: the recording is written, the hash printed.
    InterruptGuard guard;
    status = RunWindow(*window, *renderer, controller, colors);
  }
  renderer.reset();
  window.reset();
  if (status) return status;

  const Session& session = controller.GetSession();
  if (options.run.save_state_path) {
    if (Status failed = session.SaveState(*options.run.save_state_path)) return failed;
  }
  if (record) {
    std::fputs(RecordingHeader(options, controller).c_str(), record->Stream());
    std::fputs(FormatScript(controller.Recorded()).c_str(), record->Stream());
    if (Status failed = record->Commit()) return failed;
    const std::size_t events = controller.Recorded().size();
    std::printf("play: %zu event%s recorded -> %s\n", events, events == 1 ? "" : "s",
                options.record_path->c_str());
  }
  if (controller.PendingClicks() > 0) {
    const std::size_t clicks = controller.PendingClicks();
    std::printf("play: %zu click%s at step %" PRId64
                " not applied (the run ended before that step), so not recorded\n",
                clicks, clicks == 1 ? "" : "s", session.StepIndex());
  }
  if (const std::size_t others = controller.PendingEvents() - controller.PendingClicks(); others > 0) {
    std::printf("play: %zu grab, drag or release event%s at step %" PRId64
                " not applied (the run ended before that step), so not recorded\n",
                others, others == 1 ? "" : "s", session.StepIndex());
  }
  std::printf("play: stopped at step %" PRId64 " (%.3f s simulated)\n", session.StepIndex(),
              static_cast<double>(session.StepIndex()) * session.World().Def().dt);
  PrintEventSummary(session.SceneDef(), session.Events(), controller.EventsLeft(),
                    options.run.list_misses);
  std::printf("state-hash: %016" PRIx64 "\n", session.World().StateHash());
  return std::nullopt;
}

}  // namespace game
