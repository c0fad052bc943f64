// glTF 2.0's metallic-roughness surface colour (the specification's Appendix B, docs/mtoon.md) from the mesh's
// material, which passes/material/SceneMaterials binds: the shade pass draws a material without MToon with it under
// --shading mtoon (shade/shade.frag, MODEL_MTOON), as three-vrm draws such a material (three.js' MeshStandardMaterial).
// Needs common/lighting.glsl (its ambientLight, --ambient) and common/material.glsl before it.
#ifdef INKGRAPH_FRAGMENT_STAGE
uniform float materialMetallicFactor;
uniform float materialRoughnessFactor;
uniform int materialMetallicRoughnessTextured;
uniform int materialMetallicRoughnessSet;
uniform mat3 materialMetallicRoughnessTransform;
// RGBA8 storage, linear data: B is the metalness, G the roughness (glTF).
layout(binding = 13) uniform sampler2D materialMetallicRoughnessTexture;

const float kPbrPi = 3.14159265358979;
// The directional light's irradiance on a surface facing it. Lambert's BRDF is c_diff / pi, so this lights the lit
// side with its diffuse colour, as MToon's lit side is its base colour times a white light of 1, and as three-vrm's
// scenes light three.js' physically based materials (a directional light of intensity pi).
const float kPbrLightIrradiance = kPbrPi;
// The reflectance of a dielectric at normal incidence (glTF: an index of refraction of 1.5).
const float kPbrDielectricF0 = 0.04;
// The least roughness, three.js' own floor: the GGX peak 1 / (pi alpha^2) runs to infinity as roughness goes to 0
// (at 0 it is 0 / 0), a highlight of a single light direction that no pixel would resolve.
const float kPbrMinRoughness = 0.0525;

// Trowbridge-Reitz (GGX) normal distribution D for the half-vector cosine n.h and alpha = roughness^2.
float pbrDistribution(float nDotH, float alpha) {
    float alphaSquared = alpha * alpha;
    float denominator = nDotH * nDotH * (alphaSquared - 1.0) + 1.0;
    return alphaSquared / (kPbrPi * denominator * denominator);
}

// Smith's height-correlated masking-shadowing for GGX, folded with the microfacet BRDF's 1 / (4 n.l n.v) into the
// visibility V = G / (4 n.l n.v) (Heitz 2014, as glTF's Appendix B writes it). Finite where n.v or n.l is 0.
float pbrVisibility(float nDotL, float nDotV, float alpha) {
    float alphaSquared = alpha * alpha;
    float viewMasking = nDotL * sqrt(nDotV * nDotV * (1.0 - alphaSquared) + alphaSquared);
    float lightShadowing = nDotV * sqrt(nDotL * nDotL * (1.0 - alphaSquared) + alphaSquared);
    return 0.5 / max(viewMasking + lightShadowing, 1e-6);
}

// Schlick's Fresnel with reflectance f0 at normal incidence and 1 at grazing incidence.
vec3 pbrFresnel(vec3 f0, float vDotH) {
    float grazing = 1.0 - clamp(vDotH, 0.0, 1.0);
    float grazing2 = grazing * grazing;
    return f0 + (1.0 - f0) * (grazing2 * grazing2 * grazing);
}

// The surface's linear colour for base colour `base` (linear, with vertex colours), unit normal n (turned toward the
// viewer), unit l toward the light and unit v toward the eye: (Lambert diffuse + GGX specular) times n.l times the
// light, plus the ambient light on the diffuse colour. The diffuse term is three.js' (the diffuse colour over pi, not
// weighted by 1 - F as Appendix B's fresnel_mix weights it): the picture is meant to match three-vrm's.
vec3 pbrColor(vec3 base, vec3 n, vec3 l, vec3 v) {
    float metallic = materialMetallicFactor;
    float roughness = materialRoughnessFactor;
    if (materialMetallicRoughnessTextured != 0) {
        vec4 texel = texture(materialMetallicRoughnessTexture,
                             materialTexcoord(materialMetallicRoughnessSet, materialMetallicRoughnessTransform));
        metallic *= texel.b;
        roughness *= texel.g;
    }
    metallic = clamp(metallic, 0.0, 1.0);
    float alpha = clamp(roughness, kPbrMinRoughness, 1.0);
    alpha *= alpha;
    vec3 diffuseColor = base * (1.0 - metallic);
    vec3 f0 = mix(vec3(kPbrDielectricF0), base, metallic);

    vec3 color = ambientLight * diffuseColor;
    float nDotL = dot(n, l);
    if (nDotL <= 0.0) return color;
    // At a silhouette an interpolated normal may face slightly away from the eye; the lobe is then seen edge-on.
    float nDotV = clamp(dot(n, v), 0.0, 1.0);
    vec3 halfway = l + v;
    float halfwayLength = length(halfway);
    // l = -v (the light straight behind the eye's ray) leaves no half vector; the normal stands in.
    vec3 h = halfwayLength > 0.0 ? halfway / halfwayLength : n;
    float nDotH = clamp(dot(n, h), 0.0, 1.0);
    vec3 specular = pbrFresnel(f0, dot(v, h)) * (pbrVisibility(nDotL, nDotV, alpha) * pbrDistribution(nDotH, alpha));
    return color + (diffuseColor / kPbrPi + specular) * (nDotL * kPbrLightIrradiance);
}
#endif
