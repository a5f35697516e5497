// robotd_client_options as the C++ client's ClientOptions.
#pragma once

#include "robotd/client/options.hpp"
#include "robotd/robotd.h"

namespace robotd::c {

/// `options` over the environment's defaults, which also supply the DDS Security identity.
ClientOptions to_client_options(const robotd_client_options& options);

}  // namespace robotd::c
