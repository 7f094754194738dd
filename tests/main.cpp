// main.cpp - the doctest test runner: every tests/*.cpp file is linked into this one program.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
