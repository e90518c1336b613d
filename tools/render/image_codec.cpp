// libcurvenet_image.so: the OpenImageIO encoder behind image_codec.h.
#include "image_codec.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <exception>
#include <string>
#include <type_traits>
#include <vector>

namespace {

int fail(char *error, std::size_t size, const std::string &message) {
  if (error && size) std::snprintf(error, size, "%s", message.c_str());
  return 1;
}

int encode(const curvenet_image_request &request, curvenet_image_sink sink, void *context, char *error,
           std::size_t errorSize) {
  const OIIO::TypeDesc type = request.float_pixels ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(request.width, request.height, request.channels, type);
  if (request.channel_names) spec.channelnames.assign(request.channel_names, request.channel_names + request.channels);
  spec.alpha_channel = request.alpha_channel;
  for (int k = 0; k < request.attribute_count; ++k) {
    const curvenet_image_attribute &a = request.attributes[k];
    if (a.text) spec.attribute(a.key, a.text);
    else spec.attribute(a.key, a.number);
  }

  auto out = OIIO::ImageOutput::create(request.format);
  if (!out) return fail(error, errorSize, "no " + std::string(request.format) + " writer in OpenImageIO: " + OIIO::geterror());
  // Encoded into memory (an OIIO IOProxy): the caller writes the file.
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);
  if (!out->supports("ioproxy") || !out->set_ioproxy(&memory))
    return fail(error, errorSize, "the OpenImageIO writer cannot encode into memory");
  if (!out->open(request.name, spec)) return fail(error, errorSize, "cannot encode the image: " + out->geterror());
  if (!out->write_image(type, request.pixels)) return fail(error, errorSize, "encoding failed: " + out->geterror());
  if (!out->close()) return fail(error, errorSize, "encoding failed: " + out->geterror());
  sink(context, encoded.data(), encoded.size());
  return 0;
}

} // namespace

extern "C" __attribute__((visibility("default"))) int curvenet_image_encode(const curvenet_image_request *request,
                                                                           curvenet_image_sink sink, void *context,
                                                                           char *error, size_t errorSize) {
  if (!request || request->abi != CURVENET_IMAGE_ABI)
    return fail(error, errorSize,
                "image module ABI " + std::to_string(CURVENET_IMAGE_ABI) + " does not match the caller's " +
                    (request ? std::to_string(request->abi) : std::string("(none)")));
  try {
    return encode(*request, sink, context, error, errorSize);
  } catch (const std::exception &e) {
    return fail(error, errorSize, std::string("encoding failed: ") + e.what());
  } catch (...) {
    return fail(error, errorSize, "encoding failed");
  }
}

// Compile-time check that the definition matches the header's function type.
static_assert(std::is_same_v<decltype(&curvenet_image_encode), curvenet_image_encode_fn>);
