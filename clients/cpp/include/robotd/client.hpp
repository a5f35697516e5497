// Umbrella header of the robotd C++ client library.
#pragma once

#include "robotd/client/client.hpp"
#include "robotd/client/control_loop.hpp"
#include "robotd/client/options.hpp"
#include "robotd/client/policy_data_publisher.hpp"
#include "robotd/client/session.hpp"
#include "robotd/client/subscription.hpp"
#include "robotd/messages.hpp"
#include "robotd/result.hpp"
