/* The renderer's image encoder, a module loaded on first use.
 *
 * OpenImageIO on Debian 12 brings about 250 shared libraries with it (video,
 * camera-raw, DICOM and HEIF codecs among them); a program that links it
 * pays about 0.2 s of symbol binding at every start, whatever it then does.
 * The encoder therefore lives in its own module, libcurvenet_image.so, which
 * the renderer opens (dlopen) the first time it writes an image: `curvenet
 * list`, `check` and `tessellate` start without it. The interface is plain C
 * so that the two sides need to agree on nothing but this header.
 */
#ifndef CURVENET_TOOLS_IMAGE_CODEC_H
#define CURVENET_TOOLS_IMAGE_CODEC_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Bumped whenever curvenet_image_request changes; the module refuses others. */
#define CURVENET_IMAGE_ABI 1
/** The module's one entry point (a curvenet_image_encode_fn). */
#define CURVENET_IMAGE_ENCODE_SYMBOL "curvenet_image_encode"

/** One metadata attribute of the image: text, or a float when `text` is NULL. */
typedef struct curvenet_image_attribute {
  const char *key;
  const char *text;
  float number;
} curvenet_image_attribute;

/** A whole image, interleaved channels, rows from the top. */
typedef struct curvenet_image_request {
  int abi;                          /**< CURVENET_IMAGE_ABI */
  const char *format;               /**< OpenImageIO format name: "png", "openexr" */
  const char *name;                 /**< file name, for the encoder's messages only */
  int width, height, channels;
  int float_pixels;                 /**< 1: pixels are float, 0: unsigned char */
  const void *pixels;               /**< width · height · channels values */
  const char *const *channel_names; /**< `channels` names, or NULL for the defaults */
  int alpha_channel;                /**< index of the alpha channel, or −1 */
  int attribute_count;              /**< attributes, set in this order */
  const curvenet_image_attribute *attributes;
} curvenet_image_request;

/** Receives the encoded bytes (possibly in several calls, in order). */
typedef void (*curvenet_image_sink)(void *context, const void *bytes, size_t size);

/** Encodes `request` into `sink`. Returns 0, or non-zero with a message in
 *  `error` (at most `error_size` bytes, NUL-terminated); never throws. */
typedef int (*curvenet_image_encode_fn)(const curvenet_image_request *request, curvenet_image_sink sink,
                                        void *context, char *error, size_t error_size);

#ifdef __cplusplus
}
#endif

#endif
