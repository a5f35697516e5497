// Cyclone DDS's own messages (its warnings and errors: a sample it could not deserialise, a
// malformed packet, ...) routed into robotd's log instead of straight to stderr. Each is
// counted (SurfaceCounters.dds_log_messages), escaped, cut to a bounded line and rate-limited
// per place in Cyclone's source, so a burst of bad samples costs a few lines, not one each.
#pragma once

#include <dds/dds.h>

#include "app/throttled_log.hpp"
#include "dds/surface_counters.hpp"

namespace robotd::dds {

class DdsLogSink {
 public:
  /// Installs the sink for the whole process; create it before the first participant.
  explicit DdsLogSink(SurfaceCounterSet& counters);
  DdsLogSink(const DdsLogSink&) = delete;
  DdsLogSink& operator=(const DdsLogSink&) = delete;
  /// Gives Cyclone back its default sink (stderr); Cyclone no longer calls this one after.
  ~DdsLogSink();

 private:
  static void write(void* self, const dds_log_data_t* data);

  SurfaceCounterSet& counters_;
  app::ThrottledLog log_;
};

}  // namespace robotd::dds
