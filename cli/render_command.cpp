// crowdbake render: plan (every check that needs no GPU), then Vulkan.
#include "cli/commands.h"
#include "cli/render_device.h"
#include "cli/render_plan.h"
#include "crowdbake/pipeline/error.h"

namespace crowdbake::cli {

int run_render(const RenderSettings& s) {
  RenderPlan plan = plan_render(s);
  auto context = open_vulkan(s.validation);
  // note: transitional until crowdbake_gpu's Renderer lands (helper "draw").
  throw input_error("vulkan",
                    "the renderer is not built yet (device: " + context->device_name() + ")");
}

}  // namespace crowdbake::cli
