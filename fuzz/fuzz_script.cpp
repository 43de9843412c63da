// libFuzzer target: input scripts through game::ParseScript; every script it accepts must come
// back bit for bit through FormatScript, since `play --record` relies on that round trip.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "game/script.h"

namespace {

[[noreturn]] void Fail(const char* what) {
  std::fprintf(stderr, "%s\n", what);
  std::abort();
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  game::Expected<std::vector<game::InputEvent>> events = game::ParseScript(text, "fuzz.script");
  if (!events.HasValue()) {
    const std::string& message = events.Error().message;
    if (events.Error().exit_code != game::kExitBadInput) Fail("rejected with the wrong exit code");
    if (message.rfind("fuzz.script:", 0) != 0) Fail("message does not name the file");
    if (message.find('\n') != std::string::npos) Fail("message is more than one line");
    return 0;
  }
  const std::string formatted = game::FormatScript(events.Value());
  game::Expected<std::vector<game::InputEvent>> again = game::ParseScript(formatted, "formatted");
  if (!again.HasValue()) Fail("FormatScript wrote a script ParseScript rejects");
  const std::vector<game::InputEvent>& a = events.Value();
  const std::vector<game::InputEvent>& b = again.Value();
  if (a.size() != b.size()) Fail("round trip changed the number of events");
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].step != b[i].step || a[i].kind != b[i].kind || !SameBits(a[i].at.x, b[i].at.x) ||
        !SameBits(a[i].at.y, b[i].at.y)) {
      Fail("round trip changed an event");
    }
  }
  return 0;
}
