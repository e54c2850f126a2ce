# The offscreen renderer and the golden-image comparator (tools/render/).
#   build/bin/hylo-render    plan + map (+ trajectory) -> PNG, OSMesa + libpng + FreeType
#   build/bin/hylo-pngdiff   golden comparison with a tolerance, diff images
# Link -lOSMesa and never -lGL (docs/deps.md: with -lGL every call is a no-op).

RENDER_CFLAGS := $(NODE_CFLAGS) $(OSMESA_CFLAGS) $(PNG_CFLAGS) $(FREETYPE_CFLAGS)
RENDER_INC := $(NODE_INC) -Itools/render
RENDER_LIBS := $(OSMESA_LIBS) $(PNG_LIBS) $(FREETYPE_LIBS) $(LCM_LIBS) -lm
RENDER_OBJS := $(addprefix $(BUILD)/obj/tools/render/,canvas.o input.o views.o main.o)

$(BUILD)/obj/tools/render/%.o: tools/render/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(RENDER_CFLAGS) $(DEP_FLAGS) $(RENDER_INC) -c $< -o $@

HYLO_RENDER := $(BUILD)/bin/hylo-render
$(HYLO_RENDER): $(RENDER_OBJS) $(BUILD)/obj/node/registry.o $(BUILD)/obj/node/registry_models.o $(NODE_MSG_OBJS) $(MSG_OBJS) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(RENDER_LIBS) -o $@

HYLO_PNGDIFF := $(BUILD)/bin/hylo-pngdiff
$(HYLO_PNGDIFF): $(BUILD)/obj/tools/render/pngdiff.o
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(PNG_LIBS) -o $@

ALL_TARGETS += $(HYLO_RENDER) $(HYLO_PNGDIFF)

# The renderer with the synthetic test robot of tests/node (its roadmap).
HYLO_RENDER_SYNTH := $(BUILD)/test/render/hylo-render-synthetic
$(HYLO_RENDER_SYNTH): $(RENDER_OBJS) $(BUILD)/obj/node/registry.o $(BUILD)/obj/node/registry_synth.o $(NODE_MSG_OBJS) $(MSG_OBJS) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(RENDER_LIBS) -o $@
ALL_TARGETS += $(HYLO_RENDER_SYNTH)

# Drawing inputs for the renderer tests (tests/render/fake_traj.c).
FAKE_TRAJ := $(BUILD)/test/render/fake_traj
$(BUILD)/obj/render-tests/%.o: tests/render/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(DEP_FLAGS) $(NODE_INC) -c $< -o $@
$(FAKE_TRAJ): $(BUILD)/obj/render-tests/fake_traj.o $(MSG_OBJS)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(LCM_LIBS) -lm -o $@
ALL_TARGETS += $(FAKE_TRAJ)

# Renderer tests (tests/render/test_render.sh: goldens, determinism, bad input).
RENDER_SCRIPT_TESTS := tests/render/test_render.sh
$(RENDER_SCRIPT_TESTS): $(HYLO_RENDER) $(HYLO_RENDER_SYNTH) $(HYLO_PNGDIFF) $(FAKE_TRAJ) $(HYLO_SCENE) $(HYLO_LISTEN) $(HYLO_PLANNER) $(HYLO_PLANNER_SYNTH)
TESTS += $(RENDER_SCRIPT_TESTS)

# make update-goldens: rewrites tests/render/golden/ from the current renderer
# (on purpose, after a change to the pictures; review the PNGs before committing).
update-goldens: deps
	@$(MAKE) --no-print-directory all
	@UPDATE_GOLDENS=1 tests/render/test_render.sh

# make pictures: every scene's plan drawn into docs/pictures/ (for the README),
# with what each was made from recorded in docs/provenance.json.
pictures: deps
	@$(MAKE) --no-print-directory all
	@tools/pictures.sh
