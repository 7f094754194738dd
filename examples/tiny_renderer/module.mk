# examples/tiny_renderer: dsn-tiny-renderer, a small ray caster textured by the continuous mode.
$(BUILD)/obj/examples/tiny_renderer/%.o: examples/tiny_renderer/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(OFFLINE_FLAGS) $(CXXFLAGS) -c $< -o $@

$(BUILD)/bin/dsn-tiny-renderer: $(BUILD)/obj/examples/tiny_renderer/tiny_renderer.o $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $< -o $@ $(OFFLINE_LINK)

PROGRAMS += $(BUILD)/bin/dsn-tiny-renderer
TEST_SCRIPTS += examples/tiny_renderer/smoke-test
