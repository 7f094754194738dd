# Makefile - builds the runtime (libdsn.a), the offline baker (libdsn_bake.a), the tools and their small
# library (libdsn_tools.a), the tests and the examples into $(BUILD). Parts of the tree add their own
# targets through a module.mk beside them.
#
#   make            libraries and tools          make test      everything, then every test
#   make demo       the demo pictures            make bench     benchmarks (ratios to baselines)
#   make install    PREFIX=/usr/local DESTDIR=   make deps      Debian packages the build needs
#   make uninstall  the same PREFIX and DESTDIR: removes what install put there
#   make fresh-check  as root: `make demo` and `make test` on a fresh Debian root (tests/fresh-machine/)
# DSN_NO_DEPS=1 (make variable or environment) skips the package step of make deps and the other deps-*
# targets: nothing is checked or installed (you provide what they would). Without dpkg (not Debian), make
# deps installs nothing: it checks that the build's libraries are found (packaging/install-packages).

BUILD ?= build
PREFIX ?= /usr/local
PKG_CONFIG ?= pkg-config
CXXFLAGS ?= -O2 -g
CFLAGS ?= -O2 -g
LDFLAGS ?=
VERSION := $(shell sed -n 's/^#define DSN_VERSION_STRING "\(.*\)"/\1/p' include/dsn/dsn.h)

# cmake: the install test builds a consumer with find_package(dsn); time and valgrind: the peak memory
# and uninitialised-read checks of the tools' tests.
DEPS_PACKAGES := libkissfft-dev libstb-dev doctest-dev pkg-config cmake time valgrind

WARNINGS := -Wall -Wextra -Werror -Wshadow
COMMON_FLAGS := -ffp-contract=off -Iinclude -Iruntime -MMD -MP
# The runtime is a freestanding-friendly C++11 subset: no exceptions, no RTTI, no hidden guards.
RUNTIME_FLAGS := -std=c++11 $(WARNINGS) -Wconversion -Wsign-conversion -Wcast-align -Wold-style-cast \
    -fno-exceptions -fno-rtti -fno-threadsafe-statics -fno-asynchronous-unwind-tables $(COMMON_FLAGS)
# Package flags are looked up when used (recursive =), so `make deps` can install them first.
PACKAGE_CFLAGS = $(shell $(PKG_CONFIG) --cflags kissfft-float stb 2>/dev/null)
STB_LIBS = $(shell $(PKG_CONFIG) --libs stb 2>/dev/null)
PACKAGE_LIBS = $(shell $(PKG_CONFIG) --libs kissfft-float 2>/dev/null) $(STB_LIBS)
# -I.: the offline code, the tests and the examples name a private header of another folder by its place
# in the tree ("offline/bake_internal.h", "runtime/setup/format_bytes.h"), never by a path relative to their own.
OFFLINE_FLAGS = -std=c++17 $(WARNINGS) $(COMMON_FLAGS) -I. $(PACKAGE_CFLAGS)
TEST_FLAGS = $(OFFLINE_FLAGS) -Itests

# On x86-64 the kernels (runtime/kernels/kernels.h) are built three times: the default one with the runtime's
# flags, runtime/kernels/kernel_avx2.cpp for AVX2 and runtime/kernels/kernel_avx512.cpp for AVX-512; init picks one by
# CPUID (runtime/kernels/kernel_table.cpp). Built without these flags the runtime has the default kernel alone.
ifneq ($(filter x86_64%,$(shell $(CXX) -dumpmachine 2>/dev/null)),)
RUNTIME_DISPATCH_FLAGS := -DDSN_X86_DISPATCH=1
KERNEL_AVX2_FLAGS := -mavx2
KERNEL_AVX512_FLAGS := -mavx512f -mavx512bw -mavx512dq -mavx512vl
endif
RUNTIME_SOURCES := $(wildcard runtime/*/*.cpp)
RUNTIME_OBJECTS := $(RUNTIME_SOURCES:%.cpp=$(BUILD)/obj/%.o)
OFFLINE_SOURCES := $(wildcard offline/*.cpp)
OFFLINE_OBJECTS := $(OFFLINE_SOURCES:%.cpp=$(BUILD)/obj/%.o)
# offline/tools: one program per dsn-NAME.cpp, and the library they share (libdsn_tools.a: command line,
# atomic file output, PNG output), which needs stb but neither the baker nor KissFFT.
TOOL_PROGRAM_SOURCES := $(wildcard offline/tools/dsn-*.cpp)
TOOLS_LIBRARY_SOURCES := $(filter-out $(TOOL_PROGRAM_SOURCES),$(wildcard offline/tools/*.cpp))
TOOLS_LIBRARY_OBJECTS := $(TOOLS_LIBRARY_SOURCES:%.cpp=$(BUILD)/obj/%.o)
# The installed tools; dsn-example-asset (a synthetic asset for the tests and examples) is built, not
# installed.
TOOLS := $(BUILD)/bin/dsn-bake $(BUILD)/bin/dsn-inspect $(BUILD)/bin/dsn-render $(BUILD)/bin/dsn-synth
TOOL_HELPERS := $(BUILD)/bin/dsn-example-asset
TEST_SOURCES := $(wildcard tests/*.cpp)
TEST_OBJECTS := $(TEST_SOURCES:%.cpp=$(BUILD)/obj/%.o)

LIBDSN := $(BUILD)/lib/libdsn.a
LIBDSN_BAKE := $(BUILD)/lib/libdsn_bake.a
LIBDSN_TOOLS := $(BUILD)/lib/libdsn_tools.a
TEST_RUNNER := $(BUILD)/bin/dsn-tests
OFFLINE_LINK = $(LIBDSN_TOOLS) $(LIBDSN_BAKE) $(LIBDSN) $(LDFLAGS) $(PACKAGE_LIBS) -lpthread

# Modules append to these.
PROGRAMS :=          # built by `make all`
TEST_PROGRAMS :=     # built by `make test`, not by `make all`
TEST_SCRIPTS :=      # run by `make test` after the doctest runner, each counted as one test
BENCH_PROGRAMS :=    # built and run by `make bench`; built (not run) by `make test`
WEB_BENCH_PROGRAMS := # run by `make bench` only: they need the web toolchain (`make deps-web`)
INSTALL_PROGRAMS :=  # copied to $(PREFIX)/bin by `make install`

.PHONY: all deps test demo bench install uninstall clean format format-check sanitize
all: $(LIBDSN) $(LIBDSN_BAKE) $(LIBDSN_TOOLS) $(TOOLS) $(TOOL_HELPERS)

include $(sort $(wildcard examples/*/module.mk tests/*/module.mk))

all: $(PROGRAMS)

$(BUILD)/obj/runtime/%.o: runtime/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(RUNTIME_FLAGS) $(RUNTIME_DISPATCH_FLAGS) $(CXXFLAGS) $(RUNTIME_FILE_FLAGS) -c $< -o $@
$(BUILD)/obj/runtime/kernels/kernel_avx2.o: RUNTIME_FILE_FLAGS = $(KERNEL_AVX2_FLAGS)
$(BUILD)/obj/runtime/kernels/kernel_avx512.o: RUNTIME_FILE_FLAGS = $(KERNEL_AVX512_FLAGS)

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

$(LIBDSN_TOOLS): $(TOOLS_LIBRARY_OBJECTS)
	@mkdir -p $(@D)
	rm -f $@ && $(AR) rcs $@ $^

# Each tool links what it uses: only dsn-bake and dsn-synth have the baker (and KissFFT); dsn-example-asset has the
# asset writer of libdsn_bake.a and dsn-render its image reader (--weights), the linker taking no other object.
TOOL_LINK = $(LIBDSN_TOOLS) $(LIBDSN) $(LDFLAGS) $(STB_LIBS) -lpthread
$(BUILD)/bin/dsn-%: $(BUILD)/obj/offline/tools/dsn-%.o $(LIBDSN_TOOLS) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $< -o $@ $(TOOL_LINK)
$(BUILD)/bin/dsn-bake: $(LIBDSN_BAKE)
$(BUILD)/bin/dsn-bake: TOOL_LINK = $(OFFLINE_LINK)
$(BUILD)/bin/dsn-synth: $(LIBDSN_BAKE)
$(BUILD)/bin/dsn-synth: TOOL_LINK = $(OFFLINE_LINK)
$(BUILD)/bin/dsn-render: $(LIBDSN_BAKE)
$(BUILD)/bin/dsn-render: TOOL_LINK = $(LIBDSN_TOOLS) $(LIBDSN_BAKE) $(LIBDSN) $(LDFLAGS) $(STB_LIBS) -lpthread
$(BUILD)/bin/dsn-example-asset: $(LIBDSN_BAKE)
$(BUILD)/bin/dsn-example-asset: TOOL_LINK = $(LIBDSN_TOOLS) $(LIBDSN_BAKE) $(LIBDSN) $(LDFLAGS)
# The tools' objects are kept (not deleted as intermediate files), so a second make relinks nothing.
.SECONDARY: $(TOOL_PROGRAM_SOURCES:%.cpp=$(BUILD)/obj/%.o)

$(TEST_RUNNER): $(TEST_OBJECTS) $(LIBDSN_TOOLS) $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(TEST_OBJECTS) -o $@ $(OFFLINE_LINK)

deps:
	@packaging/install-packages $(DEPS_PACKAGES)

# Build in a second make so that package flags are read after `deps` has installed the packages. The
# benchmarks are built too (not run), so that a change cannot leave them broken.
test: deps
	@$(MAKE) --no-print-directory all $(TEST_RUNNER) $(TEST_PROGRAMS) $(BENCH_PROGRAMS)
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
# Then a short pass (under a minute on 2 cores) with the runtime built without its x86 kernel copies
# (RUNTIME_DISPATCH_FLAGS empty: the default kernel alone), whose loads ASan sees where the AVX2 copy's
# vector gathers go unseen: the continuous tests but the two statistical ones (about 12 s), linked from the
# first pass's objects, and tests/sanitize/freed_asset_read.cpp, a continuous point through freed asset
# bytes, which must stop on ASan's heap-use-after-free report.
SANITIZE_DEFAULT_KERNEL = $(BUILD)/sanitize/default-kernel
sanitize: deps
	@$(MAKE) --no-print-directory test BUILD=$(BUILD)/sanitize CXX=clang++ CC=clang \
	    CXXFLAGS="-O1 -g $(SANITIZE_FLAGS)" CFLAGS="-O1 -g $(SANITIZE_FLAGS)" LDFLAGS="$(SANITIZE_FLAGS)" DSN_SANITIZE_FLAGS="$(SANITIZE_FLAGS)"
	@$(MAKE) --no-print-directory $(SANITIZE_DEFAULT_KERNEL)/lib/libdsn.a BUILD=$(SANITIZE_DEFAULT_KERNEL) \
	    RUNTIME_DISPATCH_FLAGS= CXX=clang++ CXXFLAGS="-O1 -g $(SANITIZE_FLAGS)"
	clang++ -O1 -g $(SANITIZE_FLAGS) $(BUILD)/sanitize/obj/tests/*.o -o $(SANITIZE_DEFAULT_KERNEL)/dsn-tests \
	    $(BUILD)/sanitize/lib/libdsn_tools.a $(BUILD)/sanitize/lib/libdsn_bake.a $(SANITIZE_DEFAULT_KERNEL)/lib/libdsn.a \
	    $(PACKAGE_LIBS) -lpthread
	$(SANITIZE_DEFAULT_KERNEL)/dsn-tests -tc='continuous*' -tce='continuous spectrum*,continuous statistics*'
	clang++ -std=c++17 -O1 -g $(SANITIZE_FLAGS) -Iinclude tests/sanitize/freed_asset_read.cpp \
	    -o $(SANITIZE_DEFAULT_KERNEL)/freed-asset-read $(BUILD)/sanitize/lib/libdsn_bake.a $(SANITIZE_DEFAULT_KERNEL)/lib/libdsn.a
	@if $(SANITIZE_DEFAULT_KERNEL)/freed-asset-read 2> $(SANITIZE_DEFAULT_KERNEL)/freed-asset-read.log; then \
	    echo "sanitize: freed-asset-read was not stopped by ASan"; exit 1; fi
	@grep -q 'ERROR: AddressSanitizer: heap-use-after-free' $(SANITIZE_DEFAULT_KERNEL)/freed-asset-read.log || \
	    { cat $(SANITIZE_DEFAULT_KERNEL)/freed-asset-read.log; echo "sanitize: no heap-use-after-free report"; exit 1; }
	@echo "sanitize: the default kernel's continuous tests passed and its freed-bytes read was reported"

bench: deps
	@$(MAKE) --no-print-directory all $(BENCH_PROGRAMS) $(WEB_BENCH_PROGRAMS)
	@for program in $(BENCH_PROGRAMS) $(WEB_BENCH_PROGRAMS); do echo "== $$program"; $$program || exit 1; done

# What `make install` puts under $(DESTDIR)$(PREFIX), and `make uninstall` removes: the headers, the two
# static libraries, the tools, the pkg-config files and the CMake package (lib/cmake/dsn: find_package(dsn)
# gives dsn::dsn and dsn::bake).
INSTALL_ROOT = $(DESTDIR)$(PREFIX)
INSTALLED_TOOLS = $(sort $(notdir $(TOOLS) $(INSTALL_PROGRAMS)))
INSTALLED_FILES = $(addprefix $(INSTALL_ROOT)/include/dsn/,$(notdir $(wildcard include/dsn/*.h include/dsn/*.glsl))) \
    $(INSTALL_ROOT)/lib/libdsn.a $(INSTALL_ROOT)/lib/libdsn_bake.a \
    $(addprefix $(INSTALL_ROOT)/bin/,$(INSTALLED_TOOLS)) \
    $(INSTALL_ROOT)/lib/pkgconfig/dsn.pc $(INSTALL_ROOT)/lib/pkgconfig/dsn-bake.pc \
    $(INSTALL_ROOT)/lib/cmake/dsn/dsnConfig.cmake $(INSTALL_ROOT)/lib/cmake/dsn/dsnConfigVersion.cmake
# The folders only dsn puts files in; the shared ones (bin, lib, lib/pkgconfig...) stay.
INSTALLED_FOLDERS = $(INSTALL_ROOT)/include/dsn $(INSTALL_ROOT)/lib/cmake/dsn
# The CMake package refuses a consumer of another pointer size (a 32-bit build against 64-bit libraries).
INSTALL_POINTER_SIZE = $(shell $(CXX) -dM -E -x c++ /dev/null | sed -n 's/^\#define __SIZEOF_POINTER__ //p')
INSTALL_SUBSTITUTIONS = -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' \
    -e 's|@SIZEOF_POINTER@|$(INSTALL_POINTER_SIZE)|'

install: all
	install -d $(INSTALL_ROOT)/include/dsn $(INSTALL_ROOT)/lib/pkgconfig $(INSTALL_ROOT)/lib/cmake/dsn \
	    $(INSTALL_ROOT)/bin
	install -m 644 include/dsn/*.h include/dsn/*.glsl $(INSTALL_ROOT)/include/dsn/
	install -m 644 $(LIBDSN) $(LIBDSN_BAKE) $(INSTALL_ROOT)/lib/
	$(if $(INSTALLED_TOOLS),install -m 755 $(sort $(TOOLS) $(INSTALL_PROGRAMS)) $(INSTALL_ROOT)/bin/)
	sed $(INSTALL_SUBSTITUTIONS) packaging/pkgconfig/dsn.pc.in > $(INSTALL_ROOT)/lib/pkgconfig/dsn.pc
	sed $(INSTALL_SUBSTITUTIONS) packaging/pkgconfig/dsn-bake.pc.in \
	    > $(INSTALL_ROOT)/lib/pkgconfig/dsn-bake.pc
	sed $(INSTALL_SUBSTITUTIONS) packaging/cmake/dsnConfig.cmake.in \
	    > $(INSTALL_ROOT)/lib/cmake/dsn/dsnConfig.cmake
	sed $(INSTALL_SUBSTITUTIONS) packaging/cmake/dsnConfigVersion.cmake.in \
	    > $(INSTALL_ROOT)/lib/cmake/dsn/dsnConfigVersion.cmake

uninstall:
	rm -f $(INSTALLED_FILES)
	@for folder in $(INSTALLED_FOLDERS); do [ ! -d "$$folder" ] || rmdir "$$folder" 2>/dev/null || \
	    echo "uninstall: kept $$folder: it holds files that make install did not put there"; done

FORMAT_SOURCES = $(shell git ls-files '*.cpp' '*.h' '*.c' 2>/dev/null)
format:
	clang-format -i $(FORMAT_SOURCES)
format-check:
	clang-format --dry-run --Werror $(FORMAT_SOURCES)

clean:
	rm -rf $(BUILD)

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)
