#include "cli/render_device.h"

#include "crowdbake/pipeline/error.h"

namespace crowdbake::cli {

std::unique_ptr<runtime::gpu::VulkanContext> open_vulkan(bool validation) {
  runtime::gpu::ContextOptions options;
  options.validation = validation;
  std::unique_ptr<runtime::gpu::VulkanContext> context;
  const runtime::Status status = runtime::gpu::VulkanContext::create(options, context);
  if (!status.ok()) throw input_error("vulkan", status.message());
  return context;
}

void check_validation(const runtime::gpu::VulkanContext& context) {
  if (context.validation_enabled() && context.validation_errors() > 0)
    throw input_error("vulkan", std::to_string(context.validation_errors()) +
                                    " validation error(s): " + context.validation_report());
}

}  // namespace crowdbake::cli
