// Fresnel terms shared by the material kinds (src/materials/).

// Unpolarized Fresnel reflectance at a boundary with relative index `eta`
// (inside / outside), for cosThetaI measured against the outside normal
// (negative from inside); Mitsuba's fresnel(). cosThetaT gets the
// transmitted cosine (sign opposite to cosThetaI; 0 at total internal
// reflection, where the result is 1), etaTI = eta_i / eta_t (Mitsuba's
// eta_ti: Snell's sin_t = etaTI sin_i).
float fresnelDielectric(float cosThetaI, float eta, out float cosThetaT, out float etaTI) {
  bool outside = cosThetaI >= 0.0;
  float invEta = 1.0 / eta;
  float etaIT = outside ? eta : invEta;
  etaTI = outside ? invEta : eta;
  float cosT2 = 1.0 - (1.0 - cosThetaI * cosThetaI) * (etaTI * etaTI);
  float cosI = abs(cosThetaI);
  float cosT = sqrt(max(cosT2, 0.0));
  float as = (cosI - etaIT * cosT) / (cosI + etaIT * cosT);
  float ap = (cosT - etaIT * cosI) / (cosT + etaIT * cosI);
  float r = 0.5 * (as * as + ap * ap);
  cosThetaT = pick(outside, -cosT, cosT);
  return cosI == 0.0 ? 1.0 : r;
}
