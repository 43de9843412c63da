// The GIF palette: popularity first, then a median cut (Heckbert, "Color image quantization for
// frame buffer display", SIGGRAPH 1982) over what is left, weighted by pixel counts.
#include "render/gif_palette.h"

#include <algorithm>
#include <array>
#include <map>

namespace render {

namespace {

std::uint32_t Pack(Color c) { return std::uint32_t{c.r} << 16 | std::uint32_t{c.g} << 8 | c.b; }
Color Unpack(std::uint32_t v) {
  return {static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 8),
          static_cast<std::uint8_t>(v)};
}
int Channel(std::uint32_t v, int axis) { return static_cast<int>(v >> (16 - 8 * axis) & 0xff); }

struct CountedColor {
  std::uint32_t rgb;
  std::uint64_t count;
};

// Distinct colours and how many pixels have each, in colour order (std::map: no hash order).
std::vector<CountedColor> Histogram(const Image& picture) {
  std::map<std::uint32_t, std::uint64_t> counts;
  const std::size_t pixels = static_cast<std::size_t>(picture.width) * picture.height;
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::uint8_t* p = &picture.rgb[3 * i];
    ++counts[Pack({p[0], p[1], p[2]})];
  }
  std::vector<CountedColor> colors;
  for (const auto& [rgb, count] : counts) colors.push_back({rgb, count});
  return colors;
}

// A box of the median cut: a run of `colors`.
struct Box {
  std::size_t begin;
  std::size_t end;
};

// The axis of the widest spread and how wide it is, weighted by the pixels in the box so that
// a box of many pixels is split before a box of a few stray blends.
std::pair<int, std::uint64_t> SplitPriority(const std::vector<CountedColor>& colors, Box box) {
  std::array<int, 3> low{255, 255, 255}, high{0, 0, 0};
  std::uint64_t pixels = 0;
  for (std::size_t i = box.begin; i < box.end; ++i) {
    for (int a = 0; a < 3; ++a) {
      low[a] = std::min(low[a], Channel(colors[i].rgb, a));
      high[a] = std::max(high[a], Channel(colors[i].rgb, a));
    }
    pixels += colors[i].count;
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a) {
    if (high[a] - low[a] > high[axis] - low[axis]) axis = a;
  }
  return {axis, static_cast<std::uint64_t>(high[axis] - low[axis]) * pixels};
}

// Splits the box at the weighted median of its widest axis; false when it holds one colour.
bool Split(std::vector<CountedColor>& colors, std::vector<Box>& boxes, std::size_t which) {
  const Box box = boxes[which];
  if (box.end - box.begin < 2) return false;
  const int axis = SplitPriority(colors, box).first;
  std::stable_sort(colors.begin() + box.begin, colors.begin() + box.end,
                   [axis](const CountedColor& a, const CountedColor& b) {
                     return Channel(a.rgb, axis) < Channel(b.rgb, axis);
                   });
  std::uint64_t total = 0;
  for (std::size_t i = box.begin; i < box.end; ++i) total += colors[i].count;
  std::uint64_t below = 0;
  std::size_t cut = box.begin + 1;
  for (std::size_t i = box.begin; i + 1 < box.end; ++i) {
    below += colors[i].count;
    cut = i + 1;
    if (2 * below >= total) break;
  }
  boxes[which] = {box.begin, cut};
  boxes.push_back({cut, box.end});
  return true;
}

Color WeightedMean(const std::vector<CountedColor>& colors, Box box) {
  std::array<std::uint64_t, 3> sum{0, 0, 0};
  std::uint64_t pixels = 0;
  for (std::size_t i = box.begin; i < box.end; ++i) {
    for (int a = 0; a < 3; ++a) sum[a] += Channel(colors[i].rgb, a) * colors[i].count;
    pixels += colors[i].count;
  }
  auto mean = [&](int a) { return static_cast<std::uint8_t>((sum[a] + pixels / 2) / pixels); };
  return {mean(0), mean(1), mean(2)};
}

std::vector<Color> MedianCut(std::vector<CountedColor> colors, std::size_t entries) {
  std::vector<Box> boxes;
  if (colors.empty() || entries == 0) return {};
  boxes.push_back({0, colors.size()});
  while (boxes.size() < entries) {
    std::size_t best = boxes.size();
    std::uint64_t best_priority = 0;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      if (boxes[i].end - boxes[i].begin < 2) continue;
      const std::uint64_t priority = SplitPriority(colors, boxes[i]).second;
      if (best == boxes.size() || priority > best_priority) best = i, best_priority = priority;
    }
    if (best == boxes.size() || !Split(colors, boxes, best)) break;
  }
  std::vector<Color> means;
  for (const Box& box : boxes) means.push_back(WeightedMean(colors, box));
  return means;
}

void AddUnique(std::vector<Color>& palette, Color c) {
  if (palette.size() < kGifPaletteSize && std::find(palette.begin(), palette.end(), c) == palette.end()) {
    palette.push_back(c);
  }
}

}  // namespace

std::vector<Color> BuildGifPalette(const Image& picture, std::span<const Color> keep) {
  std::vector<Color> palette;
  for (Color c : keep) AddUnique(palette, c);
  std::vector<CountedColor> colors = Histogram(picture);
  const std::uint64_t pixels = static_cast<std::uint64_t>(picture.width) * picture.height;
  // The common colours exactly, most common first (ties in colour order: stable sort).
  std::vector<CountedColor> by_count = colors;
  std::stable_sort(by_count.begin(), by_count.end(),
                   [](const CountedColor& a, const CountedColor& b) { return a.count > b.count; });
  for (const CountedColor& c : by_count) {
    if (c.count * 2000 < pixels) break;
    AddUnique(palette, Unpack(c.rgb));
  }
  // The rest, cut into the entries left.
  std::vector<CountedColor> rest;
  for (const CountedColor& c : colors) {
    if (std::find(palette.begin(), palette.end(), Unpack(c.rgb)) == palette.end()) rest.push_back(c);
  }
  for (Color c : MedianCut(std::move(rest), kGifPaletteSize - palette.size())) AddUnique(palette, c);
  return palette;
}

PaletteMapper::PaletteMapper(std::vector<Color> palette) : palette_(std::move(palette)) {}

std::uint8_t PaletteMapper::Nearest(Color c) {
  const std::uint32_t key = Pack(c);
  if (const auto it = seen_.find(key); it != seen_.end()) return it->second;
  std::size_t best = 0;
  int best_distance = 1 << 30;
  for (std::size_t i = 0; i < palette_.size(); ++i) {
    const int dr = c.r - palette_[i].r, dg = c.g - palette_[i].g, db = c.b - palette_[i].b;
    const int distance = dr * dr + dg * dg + db * db;
    if (distance < best_distance) best = i, best_distance = distance;
  }
  const auto index = static_cast<std::uint8_t>(best);
  seen_.emplace(key, index);
  return index;
}

void PaletteMapper::Map(const Image& picture, std::uint8_t* indices, int stride) {
  for (int y = 0; y < picture.height; ++y) {
    const std::uint8_t* p = &picture.rgb[static_cast<std::size_t>(y) * picture.width * 3];
    std::uint8_t* out = indices + static_cast<std::ptrdiff_t>(y) * stride;
    // Flat colour comes in long runs: one lookup a run.
    Color last{p[0], p[1], p[2]};
    std::uint8_t last_index = Nearest(last);
    for (int x = 0; x < picture.width; ++x, p += 3) {
      const Color c{p[0], p[1], p[2]};
      if (!(c == last)) last = c, last_index = Nearest(c);
      out[x] = last_index;
    }
  }
}

}  // namespace render
