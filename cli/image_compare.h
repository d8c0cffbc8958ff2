// Image error measures between RGBA8 images of equal size, over the R, G and B channels
// (alpha is the renderer's coverage, not something a viewer sees). Values are in 8-bit units.
#pragma once

#include "cli/image_rgba.h"

namespace crowdbake::cli {

// Mean of |a − b| over every pixel's R, G and B, in [0, 255].
// Throws crowdbake::Error (kUsage) when the sizes differ or an image is not valid.
double mean_abs_diff(const RgbaImage& a, const RgbaImage& b);

// Peak signal-to-noise ratio in dB: 10 · log10(255² / MSE), MSE over R, G and B.
// +infinity for identical images. Throws like mean_abs_diff.
double psnr(const RgbaImage& a, const RgbaImage& b);

// How much of the change from frame a0 to a1 is not in the change from b0 to b1: the mean of
// |(a1 − a0) − (b1 − b0)| over every pixel's R, G and B. With a = LoD renders and b = the same
// frames at full resolution, motion and animation cancel and what remains is the change that
// LoD switches add (popping). Throws like mean_abs_diff when any size differs.
double change_difference(const RgbaImage& a0, const RgbaImage& a1, const RgbaImage& b0,
                         const RgbaImage& b1);

// The fraction of pixels where the change from a0 to a1 differs from the change from b0 to b1
// by more than `threshold` in some channel of R, G, B: max_c |(a1 − a0) − (b1 − b0)| > threshold.
// Counts visible pops (a patch that changes) rather than their average over the image.
// Throws like change_difference.
double change_outliers(const RgbaImage& a0, const RgbaImage& a1, const RgbaImage& b0,
                       const RgbaImage& b1, int threshold);

}  // namespace crowdbake::cli
