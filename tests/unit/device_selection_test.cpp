// DeviceSelector parsing and the device-selection plan (no EGL needed).

#include "gl/egl_devices.hpp"
#include "glcollide/error.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace glcollide {
namespace {

using Kind = DeviceSelector::Kind;
using egl::Candidate;

TEST(DeviceSelector, ParsesAcceptedForms) {
    EXPECT_EQ(DeviceSelector::parse("auto"), (DeviceSelector{Kind::Auto, -1}));
    EXPECT_EQ(DeviceSelector::parse("software"), (DeviceSelector{Kind::Software, -1}));
    EXPECT_EQ(DeviceSelector::parse("0"), (DeviceSelector{Kind::Index, 0}));
    EXPECT_EQ(DeviceSelector::parse("3"), (DeviceSelector{Kind::Index, 3}));
    EXPECT_EQ(DeviceSelector::parse("cuda:1"), (DeviceSelector{Kind::Cuda, 1}));
}

TEST(DeviceSelector, ToStringRoundTrips) {
    for (const char* text : {"auto", "software", "0", "12", "cuda:0", "cuda:7"})
        EXPECT_EQ(DeviceSelector::parse(text).toString(), text);
}

TEST(DeviceSelector, RejectsBadTextWithAHelpfulMessage) {
    for (const char* text :
         {"", "-1", "gpu", "cuda:", "1x", "+1", " 0", "cuda:-1", "cuda:1x", "AUTO", "99999999999999999999"}) {
        try {
            DeviceSelector::parse(text);
            ADD_FAILURE() << "accepted \"" << text << "\"";
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find("\"" + std::string(text) + "\""), std::string::npos) << message;
            for (const char* form : {"auto", "software", "cuda:"})
                EXPECT_NE(message.find(form), std::string::npos) << message;
        }
    }
}

EglDeviceInfo device(int index, bool software, int cuda = -1) {
    EglDeviceInfo d;
    d.index = index;
    d.software = software;
    d.cudaDevice = cuda;
    d.extensions =
        software ? "EGL_MESA_device_software EGL_EXT_device_drm_render_node" : "EGL_EXT_device_drm";
    if (cuda >= 0) d.extensions += " EGL_NV_device_cuda";
    if (!software) d.drmRenderNode = "/dev/dri/renderD" + std::to_string(128 + index);
    return d;
}

const Candidate kSurfaceless{Candidate::Kind::Surfaceless, -1};
Candidate dev(int index) {
    return {Candidate::Kind::Device, index};
}

TEST(DevicePlan, AutoPrefersGpusThenSurfacelessThenSoftware) {
    // Mesa's list puts the software device last, NVIDIA's are merged in front (platform.md §1.6).
    const std::vector<EglDeviceInfo> devices = {device(0, false, 0), device(1, false), device(2, true)};
    const auto plan = egl::planCandidates(DeviceSelector{}, {devices, true, true, false});
    EXPECT_EQ(plan, (std::vector<Candidate>{dev(0), dev(1), kSurfaceless, dev(2)}));
}

TEST(DevicePlan, AutoOnLlvmpipeUsesSurfacelessFirst) {
    const std::vector<EglDeviceInfo> devices = {device(0, true)};
    EXPECT_EQ(egl::planCandidates(DeviceSelector{}, {devices, true, true, false}),
              (std::vector<Candidate>{kSurfaceless, dev(0)}));
    // Without device enumeration only the surfaceless platform is left.
    EXPECT_EQ(egl::planCandidates(DeviceSelector{}, {{}, false, true, false}),
              (std::vector<Candidate>{kSurfaceless}));
}

TEST(DevicePlan, AutoSkipsUnqueryableDevices) {
    std::vector<EglDeviceInfo> devices = {device(0, false), device(1, false)};
    devices[0].queryable = false;
    EXPECT_EQ(egl::planCandidates(DeviceSelector{}, {devices, true, false, false}),
              (std::vector<Candidate>{dev(1)}));
}

TEST(DevicePlan, RequireGpuDropsTheSoftwareDevice) {
    const std::vector<EglDeviceInfo> devices = {device(0, true)};
    EXPECT_EQ(egl::planCandidates(DeviceSelector{}, {devices, true, true, true}),
              (std::vector<Candidate>{kSurfaceless}));
    EXPECT_THROW(egl::planCandidates(DeviceSelector{}, {devices, true, false, true}), Error);
    EXPECT_THROW(egl::planCandidates(DeviceSelector::parse("software"), {devices, true, true, true}), Error);
}

TEST(DevicePlan, SoftwareSelectsTheSoftwareDeviceOrSurfaceless) {
    const std::vector<EglDeviceInfo> devices = {device(0, false), device(1, true)};
    EXPECT_EQ(egl::planCandidates(DeviceSelector::parse("software"), {devices, true, true, false}),
              (std::vector<Candidate>{dev(1)}));
    EXPECT_EQ(egl::planCandidates(DeviceSelector::parse("software"), {{}, false, true, false}),
              (std::vector<Candidate>{kSurfaceless}));
    EXPECT_THROW(egl::planCandidates(DeviceSelector::parse("software"), {{}, false, false, false}), Error);
}

TEST(DevicePlan, ExplicitIndexNeverFallsBack) {
    const std::vector<EglDeviceInfo> devices = {device(0, false), device(1, true)};
    EXPECT_EQ(egl::planCandidates(DeviceSelector::parse("1"), {devices, true, true, false}),
              (std::vector<Candidate>{dev(1)}));
    try {
        egl::planCandidates(DeviceSelector::parse("5"), {devices, true, true, false});
        ADD_FAILURE() << "device 5 does not exist";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("EGL device 5"), std::string::npos) << message;
        EXPECT_NE(message.find(devices[0].description()), std::string::npos) << message;
        EXPECT_NE(message.find(devices[1].description()), std::string::npos) << message;
    }
    EXPECT_THROW(egl::planCandidates(DeviceSelector::parse("0"), {devices, false, true, false}), Error);
}

TEST(DevicePlan, CudaOrdinalMatchesEglCudaDevice) {
    const std::vector<EglDeviceInfo> devices = {device(0, false, 1), device(1, false, 0), device(2, true)};
    EXPECT_EQ(egl::planCandidates(DeviceSelector::parse("cuda:0"), {devices, true, true, false}),
              (std::vector<Candidate>{dev(1)}));
    try {
        egl::planCandidates(DeviceSelector::parse("cuda:2"), {devices, true, true, false});
        ADD_FAILURE() << "cuda:2 does not exist";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cuda:2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("cuda:1"), std::string::npos) << e.what(); // lists device 0
    }
}

TEST(EglDeviceInfo, DescriptionNamesTheKeyFacts) {
    EXPECT_EQ(device(0, true).description(), "EGL device 0 (EGL_MESA_device_software, software)");
    EXPECT_EQ(device(1, false, 0).description(),
              "EGL device 1 (EGL_NV_device_cuda, EGL_EXT_device_drm, /dev/dri/renderD129, cuda:0)");
    EglDeviceInfo bare;
    bare.index = 2;
    bare.queryable = false;
    EXPECT_EQ(bare.description(), "EGL device 2 (not queryable)");
}

} // namespace
} // namespace glcollide
