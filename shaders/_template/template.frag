// The template pass (passes/_template/): copies its input, texel-exact. From an input `inputScale` times the frame
// size each pixel takes the texel at the lower-left corner (GL's origin) of its inputScale x inputScale block.
layout(binding = 0) uniform sampler2D inputColor;
uniform int inputScale;

out vec4 outColor;

void main() { outColor = texelFetch(inputColor, ivec2(gl_FragCoord.xy) * inputScale, 0); }
