// Line mask: 1.0 in the R8 target stores 255 (the depth draw writes no colour at all).
layout(location = 0) out float outLine;

void main() {
    outLine = 1.0;
}
