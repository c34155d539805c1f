#version 330 core
layout(location = 0) in vec3 aPosition;

uniform mat4 uViewProjection;
uniform mat4 uModel;

out vec3 vWorld;

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  gl_Position = uViewProjection * world;
}
