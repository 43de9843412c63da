// Stands in for the FFmpeg encoder in a build without libavcodec, libavformat and libswscale.
#include "render/video_encoder.h"

namespace render {

bool VideoSupportBuilt() { return false; }

std::unique_ptr<VideoEncoder> VideoEncoder::Open(const std::string&, const VideoSettings&,
                                                 std::string& error) {
  error = "this ballbox was built without FFmpeg's libraries, so it cannot write videos "
          "(install libavcodec-dev libavformat-dev libswscale-dev and rebuild); write PNG "
          "frames with --out instead";
  return nullptr;
}

}  // namespace render
