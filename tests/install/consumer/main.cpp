// Lists robotd's devices on the domain given as argv[1]; exits 0 if it got an answer.
#include <cstdio>
#include <cstdlib>
#include <robotd/client.hpp>

int main(int argc, char** argv) {
  robotd::ClientOptions options;
  options.domain_id = argc > 1 ? std::atoi(argv[1]) : 0;
  auto client = robotd::Client::connect(options);
  if (!client) return 1;
  auto devices = client.value().list_devices();
  if (!devices) {
    std::printf("error (%s): %s\n", robotd::to_string(devices.error().code), devices.error().message.c_str());
    return 2;
  }
  for (const auto& device : devices.value()) {
    std::printf("%s %s %zu\n", device.name.c_str(), device.driver.c_str(), device.joint_names.size());
  }
  return 0;
}
