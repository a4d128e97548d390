#include <iostream>

#include "lang2manip/app/cli_app.hpp"

int main(int argc, char** argv) { return lang2manip::runCli(argc, argv, std::cout, std::cerr); }
