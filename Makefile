# Makefile - builds the runtime (libdsn.a), the offline baker (libdsn_bake.a), the tools, the tests and
# the examples into $(BUILD). Parts of the tree add their own targets through a module.mk beside them.
#
#   make            libraries and tools          make test      everything, then every test
#   make demo       the demo pictures            make bench     benchmarks (ratios to baselines)
#   make install    PREFIX=/usr/local DESTDIR=   make deps      Debian packages the build needs

BUILD ?= build
PREFIX ?= /usr/local
PKG_CONFIG ?= pkg-config
CXXFLAGS ?= -O2 -g
CFLAGS ?= -O2 -g
LDFLAGS ?=
VERSION := $(shell sed -n 's/^#define DSN_VERSION_STRING "\(.*\)"/\1/p' include/dsn/dsn.h)

DEPS_PACKAGES := libkissfft-dev libstb-dev doctest-dev pkg-config

WARNINGS := -Wall -Wextra -Werror -Wshadow
COMMON_FLAGS := -ffp-contract=off -Iinclude -MMD -MP
# The runtime is a freestanding-friendly C++11 subset: no exceptions, no RTTI, no hidden guards.
RUNTIME_FLAGS := -std=c++11 $(WARNINGS) -Wconversion -Wsign-conversion -Wcast-align -Wold-style-cast \
    -fno-exceptions -fno-rtti -fno-threadsafe-statics -fno-asynchronous-unwind-tables $(COMMON_FLAGS)
# Package flags are looked up when used (recursive =), so `make deps` can install them first.
PACKAGE_CFLAGS = $(shell $(PKG_CONFIG) --cflags kissfft-float stb 2>/dev/null)
PACKAGE_LIBS = $(shell $(PKG_CONFIG) --libs kissfft-float stb 2>/dev/null)
OFFLINE_FLAGS = -std=c++17 $(WARNINGS) $(COMMON_FLAGS) $(PACKAGE_CFLAGS)
TEST_FLAGS = $(OFFLINE_FLAGS) -Itests

# On x86-64 the tile code is built three times, the other copies (runtime/tile_avx2.cpp and
# runtime/tile_avx512.cpp) for AVX2 and AVX-512; init picks one by CPUID (runtime/tile_dispatch.h). Built
# without these flags the runtime has one copy.
ifneq ($(filter x86_64%,$(shell $(CXX) -dumpmachine 2>/dev/null)),)
RUNTIME_DISPATCH_FLAGS := -DDSN_TILE_AVX2=1
TILE_AVX2_FLAGS := -mavx2
TILE_AVX512_FLAGS := -mavx512f -mavx512bw
endif
RUNTIME_SOURCES := $(wildcard runtime/*.cpp)
RUNTIME_OBJECTS := $(RUNTIME_SOURCES:%.cpp=$(BUILD)/obj/%.o)
OFFLINE_SOURCES := $(wildcard offline/*.cpp)
OFFLINE_OBJECTS := $(OFFLINE_SOURCES:%.cpp=$(BUILD)/obj/%.o)
TOOL_SOURCES := $(wildcard offline/tools/*.cpp)
TOOLS := $(patsubst offline/tools/%.cpp,$(BUILD)/bin/%,$(TOOL_SOURCES))
TEST_SOURCES := $(wildcard tests/*.cpp)
TEST_OBJECTS := $(TEST_SOURCES:%.cpp=$(BUILD)/obj/%.o)

LIBDSN := $(BUILD)/lib/libdsn.a
LIBDSN_BAKE := $(BUILD)/lib/libdsn_bake.a
TEST_RUNNER := $(BUILD)/bin/dsn-tests
OFFLINE_LINK = $(LIBDSN_BAKE) $(LIBDSN) $(LDFLAGS) $(PACKAGE_LIBS) -lpthread

# Modules append to these.
PROGRAMS :=          # built by `make all`
TEST_PROGRAMS :=     # built by `make test`, not by `make all`
TEST_SCRIPTS :=      # run by `make test` after the doctest runner, each counted as one test
BENCH_PROGRAMS :=    # built and run by `make bench`
INSTALL_PROGRAMS :=  # copied to $(PREFIX)/bin by `make install`

.PHONY: all deps test demo bench install clean format format-check sanitize
all: $(LIBDSN) $(LIBDSN_BAKE) $(TOOLS)

include $(sort $(wildcard examples/*/module.mk tests/*/module.mk))

all: $(PROGRAMS)

$(BUILD)/obj/runtime/%.o: runtime/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(RUNTIME_FLAGS) $(RUNTIME_DISPATCH_FLAGS) $(CXXFLAGS) $(RUNTIME_FILE_FLAGS) -c $< -o $@
$(BUILD)/obj/runtime/tile_avx2.o: RUNTIME_FILE_FLAGS = $(TILE_AVX2_FLAGS)
$(BUILD)/obj/runtime/tile_avx512.o: RUNTIME_FILE_FLAGS = $(TILE_AVX512_FLAGS)

$(BUILD)/obj/offline/%.o: offline/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(OFFLINE_FLAGS) $(CXXFLAGS) -c $< -o $@

$(BUILD)/obj/tests/%.o: tests/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(TEST_FLAGS) $(CXXFLAGS) -c $< -o $@

$(LIBDSN): $(RUNTIME_OBJECTS)
	@mkdir -p $(@D)
	rm -f $@ && $(AR) rcs $@ $^

$(LIBDSN_BAKE): $(OFFLINE_OBJECTS)
	@mkdir -p $(@D)
	rm -f $@ && $(AR) rcs $@ $^

$(BUILD)/bin/%: $(BUILD)/obj/offline/tools/%.o $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $< -o $@ $(OFFLINE_LINK)

$(TEST_RUNNER): $(TEST_OBJECTS) $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(TEST_OBJECTS) -o $@ $(OFFLINE_LINK)

deps:
	@.ci/install-packages $(DEPS_PACKAGES)

# Build in a second make so that package flags are read after `deps` has installed the packages.
test: deps
	@$(MAKE) --no-print-directory all $(TEST_RUNNER) $(TEST_PROGRAMS)
	@BUILD="$(BUILD)" tests/run-tests $(TEST_RUNNER) $(TEST_SCRIPTS)

demo: deps
	@$(MAKE) --no-print-directory all
	@if [ -x examples/demo/make-demo ]; then BUILD="$(BUILD)" examples/demo/make-demo "$(EXEMPLAR)"; \
	 else echo "demo: the baker is not there yet (build/bin/dsn-bake); nothing to show"; fi

# The whole test suite again, built with clang's AddressSanitizer and UndefinedBehaviorSanitizer; the
# first report stops the run (-fno-sanitize-recover).
# (-fsanitize=function is left out: it puts C++ type info into the runtime, which C programs link without.)
SANITIZE_FLAGS := -fsanitize=address,undefined -fno-sanitize=function -fno-sanitize-recover=all \
    -fno-omit-frame-pointer
sanitize: deps
	@$(MAKE) --no-print-directory test BUILD=$(BUILD)/sanitize CXX=clang++ CC=clang \
	    CXXFLAGS="-O1 -g $(SANITIZE_FLAGS)" CFLAGS="-O1 -g $(SANITIZE_FLAGS)" LDFLAGS="$(SANITIZE_FLAGS)" DSN_SANITIZE_FLAGS="$(SANITIZE_FLAGS)"

bench: deps
	@$(MAKE) --no-print-directory all $(BENCH_PROGRAMS)
	@for program in $(BENCH_PROGRAMS); do echo "== $$program"; $$program || exit 1; done

install: all
	install -d $(DESTDIR)$(PREFIX)/include/dsn $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/bin
	install -m 644 include/dsn/*.h include/dsn/*.glsl $(DESTDIR)$(PREFIX)/include/dsn/
	install -m 644 $(LIBDSN) $(LIBDSN_BAKE) $(DESTDIR)$(PREFIX)/lib/
	$(if $(strip $(TOOLS) $(INSTALL_PROGRAMS)),install -m 755 $(TOOLS) $(INSTALL_PROGRAMS) $(DESTDIR)$(PREFIX)/bin/)
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' .ci/dsn.pc.in \
	    > $(DESTDIR)$(PREFIX)/lib/pkgconfig/dsn.pc
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' .ci/dsn-bake.pc.in \
	    > $(DESTDIR)$(PREFIX)/lib/pkgconfig/dsn-bake.pc

FORMAT_SOURCES = $(shell git ls-files '*.cpp' '*.h' '*.c' 2>/dev/null)
format:
	clang-format -i $(FORMAT_SOURCES)
format-check:
	clang-format --dry-run --Werror $(FORMAT_SOURCES)

clean:
	rm -rf $(BUILD)

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)
