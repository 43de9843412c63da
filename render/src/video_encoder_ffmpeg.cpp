// The video encoder on FFmpeg 5.1's libraries (Debian 12): libavcodec's send_frame /
// receive_packet API, libavformat to mux, libswscale for RGB -> yuv420p. Every FFmpeg object
// belongs to one FfmpegEncoder and is freed with it; the caller owns the file's name.
#include <cmath>
#include <optional>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "render/gif_palette.h"
#include "render/video_encoder.h"

namespace render {

namespace {

std::string AvError(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

struct FormatNames {
  const char* muxer;
  const char* encoder;
};

FormatNames NamesOf(VideoFormat format) {
  switch (format) {
    case VideoFormat::kMp4: return {"mp4", "libx264"};
    case VideoFormat::kWebm: return {"webm", "libvpx-vp9"};
    case VideoFormat::kGif: return {"gif", "gif"};
  }
  return {"mp4", "libx264"};
}

// A GIF frame lasts whole hundredths of a second, and browsers show frames of 0 or 1 hundredth
// for 10: a GIF keeps the frames that fall at least 2 hundredths after the last it kept, each
// at its own rounded time, so the film still plays in real time.
constexpr std::int64_t kGifShortestDelay = 2;

std::int64_t Hundredths(double seconds) { return std::llround(100.0 * seconds); }

class FfmpegEncoder final : public VideoEncoder {
 public:
  explicit FfmpegEncoder(const VideoSettings& settings) : settings_(settings) {}
  ~FfmpegEncoder() override {
    // An abandoned film still gets its trailer: some muxers (GIF's in FFmpeg 5.1) free the
    // packet they hold back only there. The caller removes the file anyway.
    if (header_written_ && !trailer_written_) av_write_trailer(format_);
    sws_freeContext(sws_);
    av_frame_free(&frame_);
    av_packet_free(&packet_);
    avcodec_free_context(&codec_);
    if (format_ != nullptr && format_->pb != nullptr) avio_closep(&format_->pb);
    avformat_free_context(format_);
  }

  bool Open(const std::string& path, std::string& error);
  bool Write(const Image& frame, std::string& error) override;
  bool Finish(std::string& error) override;
  std::int64_t FramesKept() const override { return kept_; }

 private:
  bool OpenCodec(std::string& error);
  bool OpenFrame(std::string& error);
  bool Fill(const Image& image, std::string& error);
  bool Send(const AVFrame* frame, std::string& error);

  VideoSettings settings_;
  AVFormatContext* format_ = nullptr;
  AVCodecContext* codec_ = nullptr;
  AVStream* stream_ = nullptr;
  AVFrame* frame_ = nullptr;
  AVPacket* packet_ = nullptr;
  SwsContext* sws_ = nullptr;
  std::optional<PaletteMapper> mapper_;
  std::vector<std::uint32_t> palette_;  // ARGB, as AV_PIX_FMT_PAL8 wants it
  std::int64_t given_ = 0;
  std::int64_t kept_ = 0;
  std::int64_t last_pts_ = 0;
  bool header_written_ = false;
  bool trailer_written_ = false;
};

bool FfmpegEncoder::OpenCodec(std::string& error) {
  const FormatNames names = NamesOf(settings_.format);
  const AVCodec* codec = avcodec_find_encoder_by_name(names.encoder);
  if (codec == nullptr) {
    error = std::string("this FFmpeg has no ") + names.encoder + " encoder";
    return false;
  }
  codec_ = avcodec_alloc_context3(codec);
  stream_ = avformat_new_stream(format_, nullptr);
  if (codec_ == nullptr || stream_ == nullptr) {
    error = "out of memory";
    return false;
  }
  codec_->width = settings_.width;
  codec_->height = settings_.height;
  const bool gif = settings_.format == VideoFormat::kGif;
  codec_->pix_fmt = gif ? AV_PIX_FMT_PAL8 : AV_PIX_FMT_YUV420P;
  const AVRational rate = av_d2q(1.0 / settings_.frame_seconds, 100000);
  codec_->framerate = rate;
  // A GIF counts in hundredths of a second (its delays); the others count frames.
  codec_->time_base = gif ? AVRational{1, 100} : av_inv_q(rate);
  if (!gif) {
    // Tagged as what swscale produces, so players convert back with the same matrix.
    codec_->color_range = AVCOL_RANGE_MPEG;
    codec_->colorspace = AVCOL_SPC_BT709;
    codec_->color_primaries = AVCOL_PRI_BT709;
    codec_->color_trc = AVCOL_TRC_BT709;
  }
  if (format_->oformat->flags & AVFMT_GLOBALHEADER) codec_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;

  AVDictionary* options = nullptr;
  if (settings_.format == VideoFormat::kMp4) {
    // Flat colours and sharp edges: x264's animation tuning, high quality at a quick preset.
    av_dict_set(&options, "preset", "veryfast", 0);
    av_dict_set(&options, "tune", "animation", 0);
    av_dict_set(&options, "crf", "18", 0);
  } else if (settings_.format == VideoFormat::kWebm) {
    // Constant quality (no bit rate), and libvpx's real-time speed: its "good" mode is several
    // times slower than the simulation on these frames.
    codec_->bit_rate = 0;
    av_dict_set(&options, "crf", "30", 0);
    av_dict_set(&options, "deadline", "realtime", 0);
    av_dict_set(&options, "cpu-used", "8", 0);
    av_dict_set(&options, "row-mt", "1", 0);
  }
  const int opened = avcodec_open2(codec_, codec, &options);
  av_dict_free(&options);
  if (opened < 0) {
    error = std::string("cannot start the ") + names.encoder + " encoder: " + AvError(opened);
    return false;
  }
  const int copied = avcodec_parameters_from_context(stream_->codecpar, codec_);
  stream_->time_base = codec_->time_base;
  stream_->avg_frame_rate = rate;
  if (copied < 0) {
    error = "cannot set up the video stream: " + AvError(copied);
    return false;
  }
  return true;
}

bool FfmpegEncoder::OpenFrame(std::string& error) {
  frame_ = av_frame_alloc();
  packet_ = av_packet_alloc();
  if (frame_ == nullptr || packet_ == nullptr) {
    error = "out of memory";
    return false;
  }
  frame_->format = codec_->pix_fmt;
  frame_->width = settings_.width;
  frame_->height = settings_.height;
  if (const int got = av_frame_get_buffer(frame_, 0); got < 0) {
    error = "cannot hold a video frame: " + AvError(got);
    return false;
  }
  if (settings_.format == VideoFormat::kGif) return true;
  sws_ = sws_getContext(settings_.width, settings_.height, AV_PIX_FMT_RGB24, settings_.width,
                        settings_.height, AV_PIX_FMT_YUV420P, SWS_BILINEAR | SWS_ACCURATE_RND,
                        nullptr, nullptr, nullptr);
  if (sws_ == nullptr) {
    error = "cannot convert RGB to yuv420p at this size";
    return false;
  }
  // Full-range RGB in, limited-range BT.709 out, as tagged on the stream.
  const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
  sws_setColorspaceDetails(sws_, bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16);
  return true;
}

bool FfmpegEncoder::Open(const std::string& path, std::string& error) {
  av_log_set_level(AV_LOG_QUIET);  // failures are reported through `error`, as one line
  const FormatNames names = NamesOf(settings_.format);
  if (const int made = avformat_alloc_output_context2(&format_, nullptr, names.muxer, path.c_str());
      made < 0 || format_ == nullptr) {
    error = std::string("cannot set up a ") + names.muxer + " file: " + AvError(made);
    return false;
  }
  // No muxing date or random segment id (WebM writes both): the same film gives the same bytes.
  format_->flags |= AVFMT_FLAG_BITEXACT;
  if (!OpenCodec(error) || !OpenFrame(error)) return false;
  if (const int opened = avio_open(&format_->pb, path.c_str(), AVIO_FLAG_WRITE); opened < 0) {
    error = "cannot write: " + AvError(opened);
    return false;
  }
  AVDictionary* options = nullptr;
  // The index up front, so a browser can start playing before the whole file has arrived.
  if (settings_.format == VideoFormat::kMp4) av_dict_set(&options, "movflags", "+faststart", 0);
  const int written = avformat_write_header(format_, &options);
  av_dict_free(&options);
  if (written < 0) {
    error = "cannot write: " + AvError(written);
    return false;
  }
  header_written_ = true;
  return true;
}

bool FfmpegEncoder::Fill(const Image& image, std::string& error) {
  if (const int ok = av_frame_make_writable(frame_); ok < 0) {
    error = "cannot hold a video frame: " + AvError(ok);
    return false;
  }
  if (settings_.format != VideoFormat::kGif) {
    const std::uint8_t* source[1] = {image.rgb.data()};
    const int stride[1] = {image.width * 3};
    sws_scale(sws_, source, stride, 0, image.height, frame_->data, frame_->linesize);
    return true;
  }
  if (!mapper_) {
    // One palette for the whole film, from its first frame: the same palette every frame lets
    // the GIF encoder write only the part of each frame that changed.
    const std::vector<Color> palette = BuildGifPalette(image, settings_.gif_keep);
    palette_.assign(kGifPaletteSize, 0xff000000u);
    for (std::size_t i = 0; i < palette.size(); ++i) {
      palette_[i] = 0xff000000u | std::uint32_t{palette[i].r} << 16 |
                    std::uint32_t{palette[i].g} << 8 | palette[i].b;
    }
    mapper_.emplace(palette);
  }
  std::copy(palette_.begin(), palette_.end(), reinterpret_cast<std::uint32_t*>(frame_->data[1]));
  mapper_->Map(image, frame_->data[0], frame_->linesize[0]);
  return true;
}

bool FfmpegEncoder::Send(const AVFrame* frame, std::string& error) {
  int ret = avcodec_send_frame(codec_, frame);
  if (ret < 0) {
    error = "the encoder failed: " + AvError(ret);
    return false;
  }
  while ((ret = avcodec_receive_packet(codec_, packet_)) == 0) {
    if (settings_.format == VideoFormat::kGif) {
      // Only the last frame's delay comes from its duration; the others are pts differences.
      packet_->duration = std::max(kGifShortestDelay, Hundredths(settings_.frame_seconds));
    }
    av_packet_rescale_ts(packet_, codec_->time_base, stream_->time_base);
    packet_->stream_index = stream_->index;
    if (const int written = av_interleaved_write_frame(format_, packet_); written < 0) {
      error = "cannot write: " + AvError(written);
      return false;
    }
  }
  if (ret != AVERROR(EAGAIN) && ret != AVERROR_EOF) {
    error = "the encoder failed: " + AvError(ret);
    return false;
  }
  return true;
}

bool FfmpegEncoder::Write(const Image& image, std::string& error) {
  const std::int64_t index = given_++;
  std::int64_t pts = index;
  if (settings_.format == VideoFormat::kGif) {
    pts = Hundredths(static_cast<double>(index) * settings_.frame_seconds);
    if (kept_ > 0 && pts < last_pts_ + kGifShortestDelay) return true;
  }
  if (!Fill(image, error)) return false;
  frame_->pts = pts;
  last_pts_ = pts;
  ++kept_;
  return Send(frame_, error);
}

bool FfmpegEncoder::Finish(std::string& error) {
  if (!Send(nullptr, error)) return false;  // drains the frames the encoder holds back
  trailer_written_ = true;
  if (const int ended = av_write_trailer(format_); ended < 0) {
    error = "cannot write: " + AvError(ended);
    return false;
  }
  if (const int closed = avio_closep(&format_->pb); closed < 0) {
    error = "cannot write: " + AvError(closed);
    return false;
  }
  return true;
}

}  // namespace

bool VideoSupportBuilt() { return true; }

std::unique_ptr<VideoEncoder> VideoEncoder::Open(const std::string& path,
                                                 const VideoSettings& settings,
                                                 std::string& error) {
  auto encoder = std::make_unique<FfmpegEncoder>(settings);
  if (!encoder->Open(path, error)) return nullptr;
  return encoder;
}

}  // namespace render
