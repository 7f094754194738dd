# tests/scripts: shell tests run by `make test`, each counted as one test.
TEST_SCRIPTS += tests/scripts/install-and-link
TEST_SCRIPTS += tests/scripts/check-freestanding
TEST_SCRIPTS += tests/scripts/bake-errors tests/scripts/bake-roundtrip tests/scripts/render-smoke tests/scripts/cli-conventions
TEST_SCRIPTS += tests/scripts/render-budget
TEST_SCRIPTS += tests/scripts/check-public-header
TEST_SCRIPTS += tests/scripts/synth-errors
TEST_SCRIPTS += tests/scripts/output-signals tests/scripts/bake-concurrent
TEST_SCRIPTS += tests/scripts/image-input-valgrind
TEST_SCRIPTS += tests/scripts/histogram-build-options
TEST_SCRIPTS += tests/scripts/deps-without-dpkg tests/scripts/test-graph-toolchains
TEST_SCRIPTS += tests/scripts/readme-quick-start
TEST_SCRIPTS += tests/scripts/runtime-structure
TEST_SCRIPTS += tests/scripts/build-variants
