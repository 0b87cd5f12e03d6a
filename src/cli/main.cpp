// coons — discrete Coons patches from the command line. See README.md and docs/formats.md.
#include "registry.h"

int main(int argc, char** argv) { return coons::cli::run(argc, argv); }
