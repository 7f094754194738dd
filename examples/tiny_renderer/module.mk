# examples/tiny_renderer: dsn-tiny-renderer, a small ray caster textured by the continuous mode. It links
# the runtime only (and stb_image_write for its PNG), as a renderer of the user's would.
$(BUILD)/obj/examples/tiny_renderer/%.o: examples/tiny_renderer/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(OFFLINE_FLAGS) $(CXXFLAGS) -c $< -o $@

$(BUILD)/bin/dsn-tiny-renderer: $(BUILD)/obj/examples/tiny_renderer/tiny_renderer.o $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $< -o $@ $(LIBDSN) $(LDFLAGS) $(STB_LIBS) -lpthread

PROGRAMS += $(BUILD)/bin/dsn-tiny-renderer
TEST_SCRIPTS += examples/tiny_renderer/smoke-test
