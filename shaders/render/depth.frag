#version 430 core
// Shadow pass: depth only.

void main() {}
