// LoD selection arithmetic, bit-identical to the CPU's LodSelectJob (lod_select_job.h: lod_log,
// lod_exp, lod_area_distance, lod_weight_root). Every operation below appears in the same
// order in runtime/src/lod_select_job.cpp; `precise` forbids fused multiply-adds and
// reassociation, so each +, −, ·, / is one correctly rounded IEEE double operation as on the
// CPU. Change both files together (tests/runtime/gpu/compute_*_test.cpp compare them).
#ifndef CROWDBAKE_LOD_MATH_GLSL
#define CROWDBAKE_LOD_MATH_GLSL

const double kLn2Hi = 6.93147180369123816490e-01lf;
const double kLn2Lo = 1.90821492927058770002e-10lf;

double lod_log(double x) {
  // note: callers pass x > 0 finite (areas and distances); the CPU's special cases never occur.
  int e;
  precise double m = frexp(x, e);
  if (m < 0.7071067811865476lf) {
    m = m * 2.0lf;
    e = e - 1;
  }
  precise double s = (m - 1.0lf) / (m + 1.0lf);
  precise double z = s * s;
  precise double p = 0.043478260869565216lf;
  p = p * z + 0.047619047619047616lf;
  p = p * z + 0.05263157894736842lf;
  p = p * z + 0.058823529411764705lf;
  p = p * z + 0.06666666666666667lf;
  p = p * z + 0.07692307692307693lf;
  p = p * z + 0.09090909090909091lf;
  p = p * z + 0.1111111111111111lf;
  p = p * z + 0.14285714285714285lf;
  p = p * z + 0.2lf;
  p = p * z + 0.3333333333333333lf;
  p = p * z + 1.0lf;
  precise double k = double(e);
  precise double result = k * kLn2Hi + (k * kLn2Lo + (2.0lf * s) * p);
  return result;
}

double lod_exp(double x) {
  if (isnan(x)) return x;
  if (x > 709.0lf) return 1.0lf / 0.0lf;
  if (x < -700.0lf) return 0.0lf;
  precise double k = floor(x * 1.4426950408889634lf + 0.5lf);
  precise double r = (x - k * kLn2Hi) - k * kLn2Lo;
  precise double p = 7.647163731819816e-13lf;
  p = p * r + 1.1470745597729725e-11lf;
  p = p * r + 1.6059043836821613e-10lf;
  p = p * r + 2.08767569878681e-09lf;
  p = p * r + 2.505210838544172e-08lf;
  p = p * r + 2.755731922398589e-07lf;
  p = p * r + 2.7557319223985893e-06lf;
  p = p * r + 2.48015873015873e-05lf;
  p = p * r + 0.0001984126984126984lf;
  p = p * r + 0.001388888888888889lf;
  p = p * r + 0.008333333333333333lf;
  p = p * r + 0.041666666666666664lf;
  p = p * r + 0.16666666666666666lf;
  p = p * r + 0.5lf;
  p = p * r + 1.0lf;
  p = p * r + 1.0lf;
  return ldexp(p, int(k));
}

// A_i (out area) and D_i (out distance) of a sphere (centre, radius), as lod_area_distance.
void lod_area_distance(vec3 centre, float radius, vec3 eye, float focal_pixels, float near_plane,
                       double screen, out double area, out double distance) {
  precise double dx = double(centre.x) - double(eye.x);
  precise double dy = double(centre.y) - double(eye.y);
  precise double dz = double(centre.z) - double(eye.z);
  precise double d = max(sqrt(dx * dx + dy * dy + dz * dz), double(near_plane));
  precise double radius_px = double(focal_pixels) * double(radius) / d;
  precise double a = min(3.14159265358979323846lf * radius_px * radius_px, screen);
  area = a;
  distance = d;
}

double lod_weight_root(double area, double distance, double alpha, double type_log_weight) {
  if (!(area > 0.0lf)) return 0.0lf;
  precise double log_w = type_log_weight + (lod_log(area) - lod_log(distance));
  precise double root = lod_exp(log_w / alpha);
  return (isinf(root) || isnan(root)) ? 0.0lf : root;
}

#endif
