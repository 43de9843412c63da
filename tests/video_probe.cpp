// The probe: libavformat demuxes, libavcodec decodes (send_packet / receive_frame), libswscale
// turns frames into RGB24 with the BT.709 matrix the encoder tags its streams with.
#include "video_probe.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/pixdesc.h>
#include <libswscale/swscale.h>
}

namespace testing {

namespace {

struct Decoder {
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  ~Decoder() {
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
  }
};

std::vector<std::uint8_t> ToRgb(const AVFrame* frame) {
  SwsContext* sws = sws_getContext(frame->width, frame->height, static_cast<AVPixelFormat>(frame->format),
                                   frame->width, frame->height, AV_PIX_FMT_RGB24,
                                   SWS_BILINEAR | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
  const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
  sws_setColorspaceDetails(sws, bt709, 0, bt709, 1, 0, 1 << 16, 1 << 16);
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(frame->width) * frame->height * 3);
  std::uint8_t* out[1] = {rgb.data()};
  const int stride[1] = {frame->width * 3};
  sws_scale(sws, frame->data, frame->linesize, 0, frame->height, out, stride);
  sws_freeContext(sws);
  return rgb;
}

void Receive(Decoder& d, const AVStream* stream, int keep_rgb, ProbedVideo& video) {
  while (avcodec_receive_frame(d.codec, d.frame) == 0) {
    const std::int64_t pts = d.frame->best_effort_timestamp;
    video.frame_seconds.push_back(static_cast<double>(pts) * av_q2d(stream->time_base));
    if (static_cast<int>(video.rgb.size()) < keep_rgb) video.rgb.push_back(ToRgb(d.frame));
    av_frame_unref(d.frame);
  }
}

}  // namespace

ProbedVideo ProbeVideo(const std::string& path, int keep_rgb) {
  ProbedVideo video;
  Decoder d;
  if (avformat_open_input(&d.format, path.c_str(), nullptr, nullptr) < 0 ||
      avformat_find_stream_info(d.format, nullptr) < 0) {
    video.error = "cannot open " + path;
    return video;
  }
  const int index = av_find_best_stream(d.format, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  if (index < 0) {
    video.error = "no video stream";
    return video;
  }
  const AVStream* stream = d.format->streams[index];
  const AVCodecParameters* par = stream->codecpar;
  video.codec = avcodec_get_name(par->codec_id);
  const char* pix = av_get_pix_fmt_name(static_cast<AVPixelFormat>(par->format));
  video.pixel_format = pix ? pix : "?";
  video.width = par->width;
  video.height = par->height;
  video.rate_num = stream->avg_frame_rate.num;
  video.rate_den = stream->avg_frame_rate.den;
  const AVCodec* decoder = avcodec_find_decoder(par->codec_id);
  d.codec = decoder ? avcodec_alloc_context3(decoder) : nullptr;
  if (!d.codec || avcodec_parameters_to_context(d.codec, par) < 0 || avcodec_open2(d.codec, decoder, nullptr) < 0) {
    video.error = "no decoder for " + video.codec;
    return video;
  }
  while (av_read_frame(d.format, d.packet) >= 0) {
    if (d.packet->stream_index == index) avcodec_send_packet(d.codec, d.packet);
    av_packet_unref(d.packet);
    Receive(d, stream, keep_rgb, video);
  }
  avcodec_send_packet(d.codec, nullptr);
  Receive(d, stream, keep_rgb, video);
  video.opened = true;
  return video;
}

}  // namespace testing
