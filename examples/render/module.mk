# examples/render: dsn-render (the rendering tool) and dsn-example-asset (a synthetic asset for tests and
# examples, written without the baker), plus the smoke test of dsn-render.
$(BUILD)/obj/examples/render/%.o: examples/render/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(OFFLINE_FLAGS) $(CXXFLAGS) -c $< -o $@

$(BUILD)/bin/dsn-render: $(BUILD)/obj/examples/render/dsn_render.o $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $< -o $@ $(OFFLINE_LINK)

$(BUILD)/bin/dsn-example-asset: $(BUILD)/obj/examples/render/dsn_example_asset.o $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $< -o $@ $(OFFLINE_LINK)

PROGRAMS += $(BUILD)/bin/dsn-render $(BUILD)/bin/dsn-example-asset
INSTALL_PROGRAMS += $(BUILD)/bin/dsn-render
TEST_SCRIPTS += examples/render/smoke-test
