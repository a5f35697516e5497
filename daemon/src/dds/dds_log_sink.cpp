#include "dds/dds_log_sink.hpp"

#include <string>
#include <string_view>

#include "app/log_text.hpp"

namespace robotd::dds {
namespace {

// Cyclone's longest messages (a malformed packet's hex dump) run to about 1 kB.
constexpr std::size_t kShownBytes = 240;

spdlog::level::level_enum level_of(std::uint32_t priority) {
  if ((priority & (DDS_LC_FATAL | DDS_LC_ERROR)) != 0) return spdlog::level::err;
  if ((priority & DDS_LC_WARNING) != 0) return spdlog::level::warn;
  return spdlog::level::info;
}

}  // namespace

DdsLogSink::DdsLogSink(SurfaceCounterSet& counters) : counters_(counters) {
  dds_set_log_sink(&DdsLogSink::write, this);
}

DdsLogSink::~DdsLogSink() { dds_set_log_sink(nullptr, nullptr); }

void DdsLogSink::write(void* self, const dds_log_data_t* data) {
  auto& sink = *static_cast<DdsLogSink*>(self);
  sink.counters_.dds_log_messages.fetch_add(1, std::memory_order_relaxed);
  std::string_view message(data->message, data->size);
  while (!message.empty() && (message.back() == '\n' || message.back() == '\r')) message.remove_suffix(1);
  // One key per place in Cyclone's source: a flood of one kind never hides another.
  const std::string key =
      std::string("dds:") + (data->file != nullptr ? data->file : "?") + ":" + std::to_string(data->line);
  sink.log_.log(level_of(data->priority), key, "DDS: " + app::log_text(message, kShownBytes));
}

}  // namespace robotd::dds
