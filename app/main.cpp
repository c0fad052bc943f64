#include "app/Render.h"

#include <iostream>

int main(int argc, char** argv) { return inkgraph::runCommandLine(argc, argv, std::cout, std::cerr); }
