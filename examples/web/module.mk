# examples/web: the runtime in the browser. `make web` builds $(BUILD)/web/, a static folder to serve as it
# is: the runtime compiled for freestanding wasm32 (dsn.wasm: clang and wasm-ld, no C library, no
# Emscripten), the JavaScript module (dsn.mjs), the baker for wasm32-wasi (dsn-bake.wasm, bake.mjs), the
# demo page with its tile and bake workers, and the demo asset baked from the demo's own exemplar.
#   make web        then: python3 -m http.server -d build/web 8000, open http://127.0.0.1:8000/
#   make web-test   the page in headless Chromium against dsn-render (examples/web/web-test)
#   make bench      also runs examples/web/bench-wasm (wasm tiles under Node against native ones)
WEB := $(BUILD)/web
WEB_WASM := $(WEB)/dsn.wasm
WEB_BAKER := $(WEB)/dsn-bake.wasm
WEB_PAGE_FILES := index.html page.js tile_worker.js dsn.mjs bake.mjs bake_worker.js
WEB_PACKAGES := clang lld libclang-rt-14-dev-wasm32 nodejs wasi-libc libc++-14-dev-wasm32 libc++abi-14-dev-wasm32
WEB_TEST_PACKAGES := chromium python3

# The runtime's flags, the same sources as every other build (new runtime files are picked up), built
# freestanding: without -ffreestanding clang turns zeroing loops into calls of memset, and with it the
# memory functions come from wasm/memory.cpp. The compiler-rt builtins cover any helper call the
# compiler emits (128-bit arithmetic; Debian files them under wasm32-wasi, the same code). The stack is 1 MiB (wasm-ld's default is 64 KiB).
WASM_CXX ?= clang++
WASM_FLAGS := --target=wasm32 -O2 -ffreestanding -nostdlib $(filter-out -MMD -MP,$(RUNTIME_FLAGS))
WASM_SOURCES = $(RUNTIME_SOURCES) examples/web/wasm/memory.cpp examples/web/wasm/web_exports.cpp
# Every function the public headers declare (those the runtime defines), and what dsn.mjs needs.
WASM_PAREN := (
WASM_EXPORTS = $(shell sed -n '/^static/d; s/^[a-z][^$(WASM_PAREN)]*[ *]\(dsn_[a-z0-9_]*\)$(WASM_PAREN).*/\1/p' include/dsn/*.h)
WASM_LINK_FLAGS = -Wl,--no-entry -Wl,-z,stack-size=1048576 -Wl,--export=__heap_base \
    -Wl,--export=dsn_web_asset_bytes $(WASM_EXPORTS:%=-Wl,--export-if-defined=%) \
    $(shell $(WASM_CXX) --target=wasm32-wasi -print-libgcc-file-name)

.PHONY: web web-test deps-web deps-web-test
deps-web:
	@packaging/install-packages $(WEB_PACKAGES)
deps-web-test: deps-web
	@packaging/install-packages $(WEB_TEST_PACKAGES)

$(WEB_WASM): $(WASM_SOURCES) $(wildcard runtime/*/*.h include/dsn/*.h examples/web/wasm/*.h)
	@mkdir -p $(@D)
	$(WASM_CXX) $(WASM_FLAGS) -Iexamples/web/wasm $(WASM_SOURCES) $(WASM_LINK_FLAGS) -o $@.tmp && mv $@.tmp $@

# The baker for the page: offline/ and the runtime for wasm32-wasi (wasi-libc, Debian's wasm32 libc++),
# with what Debian does not package for wasm32 supplied by examples/web/bake/: kissfft's C functions (on
# its header-only C++ version), stb's code, a throw that reports what() and stops, and the POSIX calls
# of the file writer that wasi-libc lacks. Objects one by one: a whole build takes minutes.
WASI_CXX ?= clang++
WASI_FLAGS = --target=wasm32-wasi --sysroot=/usr -std=c++17 -O2 -ffp-contract=off -Iinclude -Iruntime -I. \
    $(PACKAGE_CFLAGS) -include examples/web/bake/posix_missing.h
# The baker's sources only: dsn-synth's spectral synthesis (offline/synth.cpp) runs its FFTs on threads,
# which wasi has not, and the page does not use it.
WASI_SOURCES = $(filter-out offline/synth.cpp,$(OFFLINE_SOURCES)) $(RUNTIME_SOURCES) \
    $(wildcard examples/web/bake/*.cpp)
WASI_OBJECTS = $(WASI_SOURCES:%.cpp=$(BUILD)/wasi/%.o)
$(BUILD)/wasi/%.o: %.cpp $(wildcard include/dsn/*.h runtime/*/*.h offline/*.h examples/web/bake/*.h)
	@mkdir -p $(@D)
	$(WASI_CXX) $(WASI_FLAGS) -c $< -o $@
$(WEB_BAKER): $(WASI_OBJECTS)
	@mkdir -p $(@D)
	$(WASI_CXX) --target=wasm32-wasi --sysroot=/usr -mexec-model=reactor $^ -Wl,--export=dsn_web_bake \
	    -Wl,--export=dsn_web_malloc -Wl,-z,stack-size=1048576 -o $@.tmp && mv $@.tmp $@

$(WEB)/%: examples/web/%
	@mkdir -p $(@D)
	cp $< $@

# The demo texture: the demo's exemplar, baked for the continuous mode (the page zooms).
$(WEB)/demo.dsnt: $(BUILD)/bin/dsn-bake $(BUILD)/bin/dsn-demo-exemplar
	@mkdir -p $(@D)
	$(BUILD)/bin/dsn-demo-exemplar $(WEB)/demo-exemplar.png --size 256
	$(BUILD)/bin/dsn-bake $(WEB)/demo-exemplar.png -o $@ --radius 15 --interpolation bilinear --quiet

web: deps deps-web
	@$(MAKE) --no-print-directory $(WEB_WASM) $(WEB_BAKER) $(WEB)/demo.dsnt $(WEB_PAGE_FILES:%=$(WEB)/%)

web-test: deps deps-web deps-web-test
	@$(MAKE) --no-print-directory all $(WEB_WASM) $(WEB_BAKER) $(WEB)/demo.dsnt $(WEB_PAGE_FILES:%=$(WEB)/%) \
	    $(WEB_GRADIENT_NATIVE)
	@BUILD="$(BUILD)" examples/web/web-test

# module-test.mjs's native gradients (beside dsn-render, where it looks for them).
WEB_GRADIENT_NATIVE := $(BUILD)/bin/dsn-web-gradient-native
$(WEB_GRADIENT_NATIVE): $(BUILD)/obj/examples/web/gradient_native.o $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $^ -o $@ $(LDFLAGS)

# make bench: the wasm tiles under Node against the same tiles natively (examples/web/bench-wasm).
$(BUILD)/bin/dsn-web-bench-native: $(BUILD)/obj/examples/web/bench_native.o $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $< -o $@ $(OFFLINE_LINK)
$(BUILD)/obj/examples/web/%.o: examples/web/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(OFFLINE_FLAGS) $(CXXFLAGS) -c $< -o $@
examples/web/bench-wasm: $(WEB_WASM) $(WEB)/demo.dsnt $(WEB)/dsn.mjs $(BUILD)/bin/dsn-web-bench-native
bench: deps-web
WEB_BENCH_PROGRAMS += examples/web/bench-wasm
