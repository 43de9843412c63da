// Cutting a colour order's groups among threads by the bodies they move.
#include "solver/body_cut.h"

#include <cassert>

namespace engine::detail {

void BodyCut::Cut(const ContactOrder& order, std::span<const BodyIndex> lead_body,
                  std::span<const BodyIndex> lead_fixed, std::size_t body_count, int threads) {
  assert(threads >= 1 && order.strips == 0 && lead_body.size() == lead_fixed.size());
  threads_ = threads;
  const auto thread_count = static_cast<std::size_t>(threads);
  const std::size_t groups = order.group_ends.size();
  ranges_.clear();
  first_.assign(groups * thread_count + 1, 0);
  whole_.assign(groups, 0);
  scratch_.resize(thread_count);
  std::uint32_t begin = 0;
  for (std::size_t g = 0; g < groups; ++g) {
    const std::uint32_t end = order.group_ends[g];
    assert(end <= lead_body.size());
    for (std::vector<Range>& part : scratch_) part.clear();
    if (g >= order.parallel_groups || end - begin < kMinCutGroupUnits) {
      whole_[g] = 1;
      if (end > begin) scratch_[0].push_back({begin, end});
    } else {
      for (std::uint32_t run = begin; run < end;) {  // each run of one kind of lead, cut apart
        std::uint32_t run_end = run + 1;
        while (run_end < end && lead_fixed[run_end] == lead_fixed[run]) ++run_end;
        std::uint32_t from = run;
        for (std::size_t t = 0; t < thread_count; ++t) {
          std::uint32_t to = run_end;
          if (t + 1 < thread_count) {
            to = from;
            const BodyIndex next_share = ShareBegin(body_count, threads, static_cast<int>(t + 1));
            while (to < run_end && lead_body[to] < next_share) ++to;
          }
          if (to > from) scratch_[t].push_back({from, to});
          from = to;
        }
        run = run_end;
      }
    }
    for (std::size_t t = 0; t < thread_count; ++t) {
      first_[g * thread_count + t] = static_cast<std::uint32_t>(ranges_.size());
      ranges_.insert(ranges_.end(), scratch_[t].begin(), scratch_[t].end());
    }
    begin = end;
  }
  first_[groups * thread_count] = static_cast<std::uint32_t>(ranges_.size());
}

}  // namespace engine::detail
