# tests/cross: same bits everywhere. `make cross-test` measures the runtime's embedded footprint
# (tests/cross/footprint), then builds the golden program for every compiler, CPU and the emulated
# Cortex-M3 and compares their hashes with tests/cross/golden.txt (tests/cross/run-cross).
#   make cross-test CROSS_UPDATE=1   rewrites golden.txt from the reference target first (on purpose only)
#   make cross-assets                regenerates tests/cross/golden_assets.cpp (then update golden.txt)
CROSS_PACKAGES := qemu-user qemu-system-arm gcc-arm-none-eabi libnewlib-arm-none-eabi \
    libstdc++-arm-none-eabi-newlib g++-i686-linux-gnu g++-aarch64-linux-gnu g++-arm-linux-gnueabihf \
    g++-s390x-linux-gnu clang lld libclang-rt-14-dev-wasm32 nodejs
CROSS_ENV = BUILD="$(BUILD)" CROSS_RUNTIME_FLAGS="$(filter-out -MMD -MP -Iinclude -Iruntime,$(RUNTIME_FLAGS))"
CROSS_ASSET_GENERATOR := $(BUILD)/cross/make-assets

.PHONY: cross-test deps-cross cross-assets
deps-cross:
	@packaging/install-packages $(CROSS_PACKAGES)

# Both checks run even when the first fails, so one report shows everything.
cross-test: deps-cross
	@status=0; \
	 $(CROSS_ENV) tests/cross/footprint || status=1; \
	 $(CROSS_ENV) tests/cross/run-cross $(if $(CROSS_UPDATE),--update) || status=1; \
	 exit $$status

$(CROSS_ASSET_GENERATOR): $(BUILD)/obj/tests/cross/make-assets.o $(LIBDSN_TOOLS) $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $< -o $@ $(OFFLINE_LINK)

cross-assets: $(CROSS_ASSET_GENERATOR)
	$(CROSS_ASSET_GENERATOR) tests/cross/golden_assets.cpp
