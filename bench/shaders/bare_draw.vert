// The bare draw of BM_GBufferVsBareDraw (bench/GBufferBench.cpp): the G-buffer's meshes, positions only.
layout(location = 0) in vec3 inPosition;

uniform mat4 clipFromModel;

void main() { gl_Position = clipFromModel * vec4(inPosition, 1.0); }
