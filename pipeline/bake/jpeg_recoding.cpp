#include "jpeg_recoding.h"

// note: jpeglib.h needs size_t and FILE declared before it.
#include <jpeglib.h>

#include <csetjmp>
#include <cstddef>
#include <cstdio>
#include <cstdlib>

#include "crowdbake/formats/pack_image.h"

namespace crowdbake {
namespace {

// libjpeg's default error handler ends the process; this one jumps back to the caller.
struct ErrorJump {
  jpeg_error_mgr manager{};
  std::jmp_buf back{};
};

[[noreturn]] void jump_back(j_common_ptr info) {
  std::longjmp(reinterpret_cast<ErrorJump*>(info->err)->back, 1);
}

void stay_quiet(j_common_ptr) {}

// The libjpeg state of one re-coding, released whichever way it ends.
struct Transcoder {
  jpeg_decompress_struct reader{};
  jpeg_compress_struct writer{};
  ErrorJump errors;  // both structs report here
  unsigned char* buffer = nullptr;
  unsigned long size = 0;

  Transcoder() {
    reader.err = writer.err = jpeg_std_error(&errors.manager);
    errors.manager.error_exit = jump_back;
    errors.manager.output_message = stay_quiet;
    jpeg_create_decompress(&reader);
    jpeg_create_compress(&writer);
  }
  ~Transcoder() {
    jpeg_destroy_compress(&writer);
    jpeg_destroy_decompress(&reader);
    std::free(buffer);
  }
  Transcoder(const Transcoder&) = delete;
  Transcoder& operator=(const Transcoder&) = delete;
};

// note: a separate function so no C++ object with a destructor lives between setjmp and a
// longjmp to it.
bool transcode(Transcoder& t, const std::vector<uint8_t>& jpeg) {
  if (setjmp(t.errors.back)) return false;
  jpeg_mem_src(&t.reader, jpeg.data(), static_cast<unsigned long>(jpeg.size()));
  if (jpeg_read_header(&t.reader, TRUE) != JPEG_HEADER_OK) return false;
  jvirt_barray_ptr* coefficients = jpeg_read_coefficients(&t.reader);
  jpeg_mem_dest(&t.writer, &t.buffer, &t.size);
  jpeg_copy_critical_parameters(&t.reader, &t.writer);
  t.writer.optimize_coding = TRUE;
  jpeg_write_coefficients(&t.writer, coefficients);
  jpeg_finish_compress(&t.writer);
  jpeg_finish_decompress(&t.reader);
  return true;
}

}  // namespace

bool recode_jpeg(const std::vector<uint8_t>& jpeg, std::vector<uint8_t>& out) {
  if (jpeg.empty()) return false;
  Transcoder t;
  if (!transcode(t, jpeg) || !t.buffer) return false;
  out.assign(t.buffer, t.buffer + t.size);
  return true;
}

uint64_t recode_jpeg_images(std::vector<PackImage>& images) {
  uint64_t saved = 0;
  for (PackImage& image : images) {
    if (image.mime_type != "image/jpeg") continue;
    PackImage recoded = image;
    if (!recode_jpeg(image.data, recoded.data) || recoded.data.size() >= image.data.size())
      continue;
    std::vector<uint8_t> before, after;
    std::string why;
    if (!decode_pack_image(image, before, why) || !decode_pack_image(recoded, after, why) ||
        before != after)
      continue;
    saved += image.data.size() - recoded.data.size();
    image.data = std::move(recoded.data);
  }
  return saved;
}

}  // namespace crowdbake
