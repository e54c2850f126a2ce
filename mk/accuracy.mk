# The trained region and the plans' clearance on the committed scenes
# (tests/scenes/), and the models'
# accuracy on the edges the planner asks for (tools/accuracy/).

# Tests on the committed scenes (tests/scenes/): no edge the planner
# evaluates lies outside its model's trained region (test_trained_region);
# every path planned keeps its robot's body and the default margin from every
# hazard, hylo/clearance.h (test_plan_clearance); the search evaluates only
# edges that could be on a path no dearer than the plan (test_lazy_evaluation).
TRAINED_REGION_TEST := $(BUILD)/test/scenes/test_trained_region
PLAN_CLEARANCE_TEST := $(BUILD)/test/scenes/test_plan_clearance
LAZY_EVALUATION_TEST := $(BUILD)/test/scenes/test_lazy_evaluation
SCENE_TESTS := $(TRAINED_REGION_TEST) $(PLAN_CLEARANCE_TEST) $(LAZY_EVALUATION_TEST)
$(SCENE_TESTS): $(BUILD)/test/scenes/%: tests/scenes/%.cpp tests/scenes/scene_suite.hpp tools/scene/planner_view.hpp \
		tools/scene/committed.hpp $(BUILD)/obj/tools/scene/scene.o $(BUILD)/obj/node/registry.o \
		$(BUILD)/obj/node/registry_models.o $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CXX) $(CXX17_FLAGS) $(LDFLAGS) -I. $(NODE_INC) $< $(filter %.o %.a,$^) $(YAML_LIBS) -lm -o $@
ALL_TARGETS += $(SCENE_TESTS)
TESTS += $(SCENE_TESTS)

# Benchmark: the models' errors on the edges the planner evaluates and the
# edges of its plans, against the trainer's exact solves
# (tools/bench/bench_accuracy.cpp; tools/accuracy/plot_accuracy.py draws
# docs/accuracy/).
BENCH_ACCURACY := $(BUILD)/bench/bin/bench_accuracy
$(BENCH_ACCURACY): tools/bench/bench_accuracy.cpp trainer/cli.hpp tools/bench/results.hpp tools/scene/planner_view.hpp tools/scene/committed.hpp $(BUILD)/obj/tools/scene/scene.o \
		$(BUILD)/obj/node/registry.o $(BUILD)/obj/node/registry_models.o $(TRAINER_LIB) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $(NODE_INC) $< $(filter %.o %.a,$^) $(TRAINER_LIBS) -lm -o $@
BENCH_TARGETS += $(BENCH_ACCURACY)

# The picture in docs/accuracy/ from the last make bench's edges (or
# ACCURACY_EDGES=path), recorded in docs/provenance.json.
ACCURACY_EDGES ?= $(BUILD)/bench/work/accuracy_edges.csv
accuracy-picture: venv-report
	.venv/bin/python tools/accuracy/plot_accuracy.py $(ACCURACY_EDGES) docs/accuracy/planner_edges.png
	tools/provenance record docs/accuracy/planner_edges.png
.PHONY: accuracy-picture

# Labels against an independent optimum (tools/accuracy/independent_optimum.py):
# pairs drawn from a planar mode's training ranges, solved by CasADi with many
# random starts and by `trainer --solve` at each of INDEPENDENT_SEGMENTS.
# Minutes per pair; MODEL=robot:mode (default ambot:ground, ground or marine).
INDEPENDENT_MODEL = $(or $(MODEL),ambot:ground)
INDEPENDENT_PROBLEMS ?= 20
INDEPENDENT_SEGMENTS ?= 20
independent-optimum: venv-bench $(TRAINER)
	@mkdir -p $(BUILD)/accuracy
	.venv/bin/python tools/accuracy/independent_optimum.py $(subst :, ,$(INDEPENDENT_MODEL)) \
		$(BUILD)/accuracy/independent-$(subst :,-,$(INDEPENDENT_MODEL)).jsonl \
		--problems $(INDEPENDENT_PROBLEMS) --segments $(INDEPENDENT_SEGMENTS)
.PHONY: independent-optimum
