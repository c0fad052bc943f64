// Lambert: deferred diffuse shading from the G-buffer's normal and base colour.
layout(binding = 0) uniform sampler2D normalTexture;    // gbuffer.normal: xyz unit normal, w coverage
layout(binding = 1) uniform sampler2D baseColorTexture; // gbuffer.baseColor: sRGB-encoded rgb, a coverage

uniform vec3 towardLightView; // unit, view space
uniform float ambient;

layout(location = 0) out vec4 outColor;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 normalAndCoverage = texelFetch(normalTexture, pixel, 0);
    if (normalAndCoverage.w == 0.0) {
        outColor = vec4(0.0);
        return;
    }
    vec3 albedo = decodeSrgb(texelFetch(baseColorTexture, pixel, 0).rgb);
    float diffuse = max(dot(normalAndCoverage.xyz, towardLightView), 0.0);
    outColor = vec4(encodeSrgb(albedo * (ambient + (1.0 - ambient) * diffuse)), 1.0);
}
