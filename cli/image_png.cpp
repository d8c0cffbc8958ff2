#include "cli/image_png.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/output_file.h"

namespace crowdbake::cli {

std::vector<uint8_t> encode_png(const RgbaImage& image) {
  if (!image.valid())
    throw Error(Error::Kind::kOutput, "png",
                "cannot encode an image of " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " pixels with " +
                    std::to_string(image.rgba.size()) + " bytes");
  // note: encoding into memory lets write_file_atomically do the writing, so a full disk or
  // an interrupt never leaves a truncated PNG under the output's name.
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto out = OIIO::ImageOutput::create("image.png", &proxy);
  if (!out) throw Error(Error::Kind::kOutput, "png", "OpenImageIO has no PNG writer");
  OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), 4,
                       OIIO::TypeDesc::UINT8);
  // note: OIIO takes pixels as premultiplied and divides by alpha when writing a PNG; ours
  // are straight RGBA, so the bytes must go to the file untouched.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (!out->open("image.png", spec) ||
      !out->write_image(OIIO::TypeDesc::UINT8, image.rgba.data()) || !out->close())
    throw Error(Error::Kind::kOutput, "png", "OpenImageIO: " + out->geterror());
  return std::vector<uint8_t>(bytes.begin(), bytes.end());
}

void write_png(const std::string& path, const RgbaImage& image) {
  std::vector<uint8_t> bytes;
  try {
    bytes = encode_png(image);
  } catch (const Error& e) {
    throw Error(Error::Kind::kOutput, path, e.what());
  }
  throw_if_failed(write_file_atomically(path, bytes));
}

RgbaImage read_png(const std::string& path) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // keep the file's straight alpha as is
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw input_error(path, "cannot read the image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw input_error(path, "image has no pixels");
  const int channels = spec.nchannels;
  std::vector<uint8_t> raw(size_t(spec.width) * spec.height * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, raw.data()))
    throw input_error(path, "cannot read the pixels: " + in->geterror());
  RgbaImage image;
  image.width = static_cast<uint32_t>(spec.width);
  image.height = static_cast<uint32_t>(spec.height);
  image.rgba.resize(size_t(image.width) * image.height * 4);
  for (size_t p = 0; p < size_t(image.width) * image.height; ++p) {
    const uint8_t* src = &raw[p * channels];
    uint8_t* dst = &image.rgba[p * 4];
    // note: 1 or 2 channels are grey (+ alpha); 3 or more are RGB(A) and extra channels go.
    for (int c = 0; c < 3; ++c) dst[c] = channels >= 3 ? src[c] : src[0];
    dst[3] = channels == 2 ? src[1] : channels >= 4 ? src[3] : 255;
  }
  return image;
}

}  // namespace crowdbake::cli
