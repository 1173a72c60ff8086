// Unsorted "over": each fragment is blended over what is already there, in submission order
// (the paper's E_random). Blend state: SRC_ALPHA, ONE_MINUS_SRC_ALPHA on RGB; alpha kept.
layout(location = 0) out vec4 outColor;

void main() {
    outColor = fetchSurfaceOrDiscard();
}
