#include "support/require_mesa.hpp"

#include "glcollide/headless_context.hpp"

#include <cstdlib>
#include <string_view>
#include <vector>

namespace glcollide::test {

std::string missingMesa() {
    const std::vector<EglDeviceInfo> devices = HeadlessContext::listDevices();
    for (const EglDeviceInfo& d : devices)
        if (d.software) return {};
    return "no EGL device advertises EGL_MESA_device_software (Mesa's llvmpipe; Debian packages libegl-mesa0 "
           "and "
           "libgl1-mesa-dri), " +
           std::to_string(devices.size()) + " EGL device(s) found";
}

bool mesaRequired() {
    const char* value = std::getenv(kRequireMesaEnvVar);
    return value != nullptr && std::string_view(value) == "1";
}

std::string mesaMissingMessage(const std::string& missing, const std::string& why) {
    std::string message = missing + "; this test needs Mesa to " + why + ". ";
    if (mesaRequired())
        message += std::string(kRequireMesaEnvVar) + "=1 makes a missing Mesa a failure";
    else
        message += "Skipped; set " + std::string(kRequireMesaEnvVar) + "=1 to make this a failure";
    return message;
}

} // namespace glcollide::test
