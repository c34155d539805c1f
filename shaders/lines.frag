#version 330 core
// Debug lines are unlit: their colour means something (red constraints, green contacts).
in vec3 vColor;
out vec4 fragColor;

void main() { fragColor = vec4(vColor, 1.0); }
