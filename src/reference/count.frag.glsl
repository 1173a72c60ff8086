// Adds 1 per surviving fragment (blend ONE/ONE into an R32F target).
layout(location = 0) out vec4 outCount;

void main() {
    fetchSurfaceOrDiscard();
    outCount = vec4(1.0);
}
