// Float B-spline evaluation for the fixed-vs-float cycle comparison on the proxy.
#include "host_tests/target_proxy/float_deboor.h"

namespace proxy {

bool float_curve_from(const core::Spline& spline, FloatCurve* out) {
  if (spline.rational || spline.control_count > kFloatMaxControl) return false;
  out->degree = spline.degree;
  out->control_count = spline.control_count;
  for (uint16_t i = 0; i < spline.knot_count; ++i) {
    out->knot[i] = (float)(spline.knot[i] - spline.knot[0]);
  }
  for (uint16_t i = 0; i < spline.control_count; ++i) {
    out->x[i] = (float)spline.control[i].x_um;
    out->y[i] = (float)spline.control[i].y_um;
  }
  return true;
}

void float_deboor_point(const FloatCurve& curve, uint16_t span, float u, float* x, float* y) {
  const uint8_t p = curve.degree;
  float dx[4];
  float dy[4];
  for (uint8_t j = 0; j <= p; ++j) {
    dx[j] = curve.x[span - p + j];
    dy[j] = curve.y[span - p + j];
  }
  for (uint8_t r = 1; r <= p; ++r) {
    for (uint8_t j = p; j >= r; --j) {
      const float left = curve.knot[span - p + j];
      const float alpha = (u - left) / (curve.knot[span + 1 + j - r] - left);
      dx[j] = (1.0f - alpha) * dx[j - 1] + alpha * dx[j];
      dy[j] = (1.0f - alpha) * dy[j - 1] + alpha * dy[j];
    }
  }
  *x = dx[p];
  *y = dy[p];
}

void float_cubic_from(const FloatCurve& curve, uint16_t span, FloatCubic* out) {
  const float a = curve.knot[span];
  const float h = curve.knot[span + 1] - a;
  float px[4];
  float py[4];
  for (uint8_t i = 0; i < 4; ++i) {
    float_deboor_point(curve, span, a + h * (float)i / 3.0f, &px[i], &py[i]);
  }
  // Interpolating cubic through t = 0, 1/3, 2/3, 1 in power basis (Newton form expanded).
  const float* ps[2] = {px, py};
  float* cs[2] = {out->cx, out->cy};
  for (uint8_t k = 0; k < 2; ++k) {
    const float* p = ps[k];
    float* c = cs[k];
    c[0] = p[0];
    c[1] = (-11.0f * p[0] + 18.0f * p[1] - 9.0f * p[2] + 2.0f * p[3]) / 2.0f;
    c[2] = 9.0f * (2.0f * p[0] - 5.0f * p[1] + 4.0f * p[2] - p[3]) / 2.0f;
    c[3] = 27.0f * (-p[0] + 3.0f * p[1] - 3.0f * p[2] + p[3]) / 6.0f;
  }
}

void float_cubic_point(const FloatCubic& cubic, float t, float* x, float* y) {
  *x = ((cubic.cx[3] * t + cubic.cx[2]) * t + cubic.cx[1]) * t + cubic.cx[0];
  *y = ((cubic.cy[3] * t + cubic.cy[2]) * t + cubic.cy[1]) * t + cubic.cy[0];
}

}  // namespace proxy
