#include "host/render/driver_settings.h"

#include <fmt/format.h>

#include "host/base/errors.h"

namespace depthprec {

namespace {

// A setting's test (set to anything but Pipeline{}'s value) and reset, made from its member, so
// each row of the table names the member once.
template <auto M>
bool differs(const Pipeline& p) {
  return p.*M != Pipeline{}.*M;
}
template <auto M>
void to_default(Pipeline& p) {
  p.*M = Pipeline{}.*M;
}

}  // namespace

const std::vector<DriverSetting>& driver_settings() {
  static const std::vector<DriverSetting> table = {
      {"divide=exact", "the driver does the perspective divide itself", differs<&Pipeline::divide>,
       nullptr},
      {"rounding=truncate", "the driver rounds binary32 arithmetic as its hardware does",
       differs<&Pipeline::rounding>, nullptr},
      {"denormals=flush", "the driver decides how its arithmetic treats denormals",
       differs<&Pipeline::denormals>, nullptr},
      {"contraction=true", "the driver's shader compiler decides contraction into FMA",
       differs<&Pipeline::contraction>, nullptr},
      {"plane", "the driver sets up and interpolates its own depth planes",
       differs<&Pipeline::plane>, to_default<&Pipeline::plane>},
      {"viewport=fma", "the driver does the viewport transform itself",
       differs<&Pipeline::viewport>, to_default<&Pipeline::viewport>},
      {"clip=llvmpipe", "the driver clips triangles its own way", differs<&Pipeline::clip>,
       to_default<&Pipeline::clip>},
      {"log=llvmpipe", "the driver's shaders compute their own log", differs<&Pipeline::log>,
       to_default<&Pipeline::log>},
      {"vertex=fma", "the driver's shader compiler forms the vertex stage's products",
       differs<&Pipeline::vertex>, to_default<&Pipeline::vertex>},
      {"conversion=llvmpipe", "the driver converts depth to its buffer's codes itself",
       differs<&Pipeline::conversion>, to_default<&Pipeline::conversion>},
      {"snap", "the driver snaps vertices to its own sub-pixel precision",
       differs<&Pipeline::snap_bits>, to_default<&Pipeline::snap_bits>},
      {"envelope", "the driver makes its own choices within its API's envelope",
       differs<&Pipeline::envelope>, to_default<&Pipeline::envelope>},
      {"shader_precision=mediump",
       "desktop OpenGL runs every shader in binary32 (GLSL 4.5 ignores precision qualifiers)",
       differs<&Pipeline::shader_precision>, nullptr},
  };
  return table;
}

void check_renderable(const Scene& scene) {
  for (const DriverSetting& d : driver_settings())
    if (d.changed(scene.pipeline))
      throw InputError(
          fmt::format("pipeline.{}: {}; render takes the driver's (leave it at its "
                      "default, or measure it with `depthprec mts`)",
                      d.setting, d.why));
  if (scene.kernel_w > scene.viewport_w || scene.kernel_h > scene.viewport_h)
    throw InputError(fmt::format("kernel {}x{} is larger than the viewport {}x{}", scene.kernel_w,
                                 scene.kernel_h, scene.viewport_w, scene.viewport_h));
}

}  // namespace depthprec
