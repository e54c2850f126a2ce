# The LCM planner node (C99, links liblcm) and its robot registry.
#   build/bin/hylo-planner   the node, with the models of onboard/models/
# The registry lists the committed model headers and the robot files' body
# radii (tools/gen-model-registry).

NODE_SRCS := onboard/node/node.c
NODE_INC := $(ONBOARD_INC) -Ionboard/msg -I$(LCM_GEN_DIR)/c -Ionboard/models
NODE_CFLAGS := $(C99_FLAGS) -D_POSIX_C_SOURCE=200809L $(LCM_CFLAGS)
MODEL_HEADERS := $(sort $(wildcard onboard/models/*.h))
REGISTRY_C := $(BUILD)/gen/models/registry.c

ROBOT_FILES := $(sort $(wildcard trainer/params/*.yaml))

$(REGISTRY_C): tools/gen-model-registry $(MODEL_HEADERS) $(ROBOT_FILES)
	@mkdir -p $(@D)
	tools/gen-model-registry $@ --params trainer/params onboard/models

$(BUILD)/obj/node/%.o: onboard/node/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(DEP_FLAGS) $(NODE_INC) -c $< -o $@

$(BUILD)/obj/node/registry_models.o: $(REGISTRY_C) $(MODEL_HEADERS)
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(DEP_FLAGS) $(NODE_INC) -c $< -o $@

NODE_OBJS := $(NODE_SRCS:onboard/node/%.c=$(BUILD)/obj/node/%.o)
# The msg adaptors, compiled against the pub/sub bindings (same structs).
NODE_MSG_OBJS := $(BUILD)/obj/node/msg_convert.o $(BUILD)/obj/node/msg_wire.o

$(BUILD)/obj/node/msg_%.o: onboard/msg/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(DEP_FLAGS) $(NODE_INC) -c $< -o $@

HYLO_PLANNER := $(BUILD)/bin/hylo-planner

$(HYLO_PLANNER): $(BUILD)/obj/node/main.o $(BUILD)/obj/node/registry.o $(NODE_OBJS) $(NODE_MSG_OBJS) $(BUILD)/obj/node/registry_models.o $(MSG_OBJS) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(LCM_LIBS) -lm -o $@

ALL_TARGETS += $(HYLO_PLANNER)

# Node tests (tests/node/): the node in-process over memq://, normal and
# ASan+UBSan builds.
NODE_TEST_SRCS := $(sort $(wildcard tests/node/test_*.c))
NODE_TEST_NAMES := $(basename $(notdir $(NODE_TEST_SRCS)))
NODE_TESTS := $(NODE_TEST_NAMES:%=$(BUILD)/test/node/%)
NODE_TESTS_SAN := $(NODE_TEST_NAMES:%=$(BUILD)/san/test/node/%)
NODE_OBJS_SAN := $(NODE_SRCS:onboard/node/%.c=$(BUILD)/san/obj/node/%.o)
NODE_MSG_OBJS_SAN := $(BUILD)/san/obj/node/msg_convert.o $(BUILD)/san/obj/node/msg_wire.o
MSG_OBJS_SAN := $(MSG_NAMES:%=$(BUILD)/san/obj/gen/lcm/c/hylo_%.o)

$(BUILD)/san/obj/node/%.o: onboard/node/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(SAN_FLAGS) $(DEP_FLAGS) $(NODE_INC) -c $< -o $@

$(BUILD)/san/obj/node/msg_%.o: onboard/msg/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(SAN_FLAGS) $(DEP_FLAGS) $(NODE_INC) -c $< -o $@

$(BUILD)/obj/node-tests/%.o: tests/node/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(CMOCKA_CFLAGS) $(DEP_FLAGS) $(NODE_INC) -Itests -c $< -o $@

$(BUILD)/san/obj/node-tests/%.o: tests/node/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(CMOCKA_CFLAGS) $(SAN_FLAGS) $(DEP_FLAGS) $(NODE_INC) -Itests -c $< -o $@

$(BUILD)/test/node/%: $(BUILD)/obj/node-tests/%.o $(NODE_OBJS) $(NODE_MSG_OBJS) $(MSG_OBJS) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(LCM_LIBS) $(CMOCKA_LIBS) -lm -o $@

$(BUILD)/san/test/node/%: $(BUILD)/san/obj/node-tests/%.o $(NODE_OBJS_SAN) $(NODE_MSG_OBJS_SAN) $(MSG_OBJS_SAN) $(ONBOARD_LIB_SAN)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $(SAN_FLAGS) $^ $(LCM_LIBS) $(CMOCKA_LIBS) -lm -o $@

# test_registry links the registry's code (with tables of its own).
$(BUILD)/test/node/test_registry: $(BUILD)/obj/node/registry.o
$(BUILD)/san/test/node/test_registry: $(BUILD)/san/obj/node/registry.o

ALL_TARGETS += $(NODE_TESTS) $(NODE_TESTS_SAN)
TESTS += $(NODE_TESTS)
TESTS_SAN += $(NODE_TESTS_SAN)

# hylo-listen: prints plans and trajectories (tools/listen/).
HYLO_LISTEN := $(BUILD)/bin/hylo-listen

$(BUILD)/obj/tools/listen/%.o: tools/listen/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(DEP_FLAGS) -Ionboard/include -Ionboard/msg -I$(LCM_GEN_DIR)/c -c $< -o $@

$(HYLO_LISTEN): $(BUILD)/obj/tools/listen/hylo_listen.o $(BUILD)/obj/node/msg_convert.o $(MSG_OBJS) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(LCM_LIBS) -lm -o $@

ALL_TARGETS += $(HYLO_LISTEN)

# hylo-scene: validates scene files and publishes their map and goal
# (tools/scene/, C++17, yaml-cpp).
HYLO_SCENE := $(BUILD)/bin/hylo-scene
SCENE_OBJS := $(BUILD)/obj/tools/scene/scene.o $(BUILD)/obj/tools/scene/hylo_scene.o

$(BUILD)/obj/tools/scene/%.o: tools/scene/%.cpp $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CXX) $(CXX17_FLAGS) $(YAML_CFLAGS) $(LCM_CFLAGS) $(DEP_FLAGS) -I. -Ionboard/include -Ionboard/msg -I$(LCM_GEN_DIR)/c -I$(LCM_GEN_DIR)/cpp -c $< -o $@

$(HYLO_SCENE): $(SCENE_OBJS) $(BUILD)/obj/node/msg_convert.o $(MSG_OBJS) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(LDFLAGS) $^ $(YAML_LIBS) $(LCM_LIBS) -o $@

ALL_TARGETS += $(HYLO_SCENE)

# A node built with the synthetic benchmark model as robot "synthetic" (ground
# only), so that the process-level tests plan with a real SVR whatever models
# are committed; and plan_check, which compares a node's plans in a log with
# the library's answers.
REGISTRY_SYNTH_C := $(BUILD)/gen/models-test/registry.c
HYLO_PLANNER_SYNTH := $(BUILD)/test/node/hylo-planner-synthetic
PLAN_CHECK := $(BUILD)/test/node/plan_check

$(REGISTRY_SYNTH_C): tools/gen-model-registry $(MODEL_HEADERS) $(SYNTH_HEADER) $(ROBOT_FILES)
	@mkdir -p $(@D)
	tools/gen-model-registry $@ --params trainer/params onboard/models $(BUILD)/gen/bench

$(BUILD)/obj/node/registry_synth.o: $(REGISTRY_SYNTH_C) $(SYNTH_HEADER)
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(DEP_FLAGS) $(NODE_INC) -I$(BUILD)/gen/bench -c $< -o $@

$(HYLO_PLANNER_SYNTH): $(BUILD)/obj/node/main.o $(BUILD)/obj/node/registry.o $(NODE_OBJS) $(NODE_MSG_OBJS) $(BUILD)/obj/node/registry_synth.o $(MSG_OBJS) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(LCM_LIBS) -lm -o $@

$(BUILD)/obj/node-tests/plan_check.o: tests/node/plan_check.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(DEP_FLAGS) $(NODE_INC) -c $< -o $@

$(PLAN_CHECK): $(BUILD)/obj/node-tests/plan_check.o $(BUILD)/obj/node/registry.o $(NODE_MSG_OBJS) $(BUILD)/obj/node/registry_synth.o $(MSG_OBJS) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ $(LCM_LIBS) -lm -o $@

ALL_TARGETS += $(HYLO_PLANNER_SYNTH) $(PLAN_CHECK)

# Process-level tests (shell, TAP): file:// logs, signals, usage.
NODE_SCRIPT_TESTS := tests/node/test_logs.sh tests/node/test_udp.sh tests/node/test_load.sh
$(NODE_SCRIPT_TESTS): $(HYLO_PLANNER_SYNTH) $(PLAN_CHECK) $(HYLO_SCENE) $(HYLO_LISTEN)
TESTS += $(NODE_SCRIPT_TESTS)

# Message-to-plan latency benchmark (tools/bench/bench_node.cpp).
BENCH_NODE := $(BUILD)/bench/bin/bench_node

$(BENCH_NODE): tools/bench/bench_node.cpp tools/bench/results.hpp $(BUILD)/obj/tools/scene/scene.o $(NODE_OBJS) $(NODE_MSG_OBJS) $(BUILD)/obj/node/registry.o $(BUILD)/obj/node/registry_synth.o $(MSG_OBJS) $(ONBOARD_LIB) | $(HYLO_PLANNER_SYNTH)
	@mkdir -p $(@D)
	$(CXX) $(CXX17_FLAGS) $(LDFLAGS) -I. $(NODE_INC) $< $(filter %.o %.a,$^) $(YAML_LIBS) $(LCM_LIBS) -lm -o $@

BENCH_TARGETS += $(BENCH_NODE)

# hylo-cost: one edge's predicted cost from the committed models (tools/cost/).
HYLO_COST := $(BUILD)/bin/hylo-cost

$(BUILD)/obj/tools/cost/%.o: tools/cost/%.c
	@mkdir -p $(@D)
	$(CC) $(NODE_CFLAGS) $(DEP_FLAGS) $(ONBOARD_INC) -c $< -o $@

$(HYLO_COST): $(BUILD)/obj/tools/cost/hylo_cost.o $(BUILD)/obj/node/registry.o $(BUILD)/obj/node/registry_models.o $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ -lm -o $@

ALL_TARGETS += $(HYLO_COST)

# hylo-envelope-tightness: envelope / cost and floor / cost of the committed
# models over random and aligned edges (tools/cost/envelope_tightness.c).
HYLO_ENVELOPE_TIGHTNESS := $(BUILD)/bin/hylo-envelope-tightness
$(HYLO_ENVELOPE_TIGHTNESS): $(BUILD)/obj/tools/cost/envelope_tightness.o $(BUILD)/obj/node/registry_models.o $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ -lm -o $@
ALL_TARGETS += $(HYLO_ENVELOPE_TIGHTNESS)
HYLO_COST_SYNTH := $(BUILD)/test/node/hylo-cost-synthetic
$(HYLO_COST_SYNTH): $(BUILD)/obj/tools/cost/hylo_cost.o $(BUILD)/obj/node/registry.o $(BUILD)/obj/node/registry_synth.o $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $^ -lm -o $@
ALL_TARGETS += $(HYLO_COST_SYNTH)
tests/node/test_logs.sh: $(HYLO_COST_SYNTH)
tests/node/test_load.sh: $(GOAL_BURST)

# goal_burst: the load client of tests/node/test_load.sh (and make bench).
GOAL_BURST := $(BUILD)/test/node/goal_burst
$(GOAL_BURST): tests/node/goal_burst.cpp $(BUILD)/obj/tools/scene/scene.o $(BUILD)/obj/node/msg_convert.o $(MSG_OBJS) $(ONBOARD_LIB) $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CXX) $(CXX17_FLAGS) -I. -Ionboard/include -Ionboard/msg -I$(LCM_GEN_DIR)/c $< $(BUILD)/obj/tools/scene/scene.o $(BUILD)/obj/node/msg_convert.o $(MSG_OBJS) $(ONBOARD_LIB) $(YAML_LIBS) $(LCM_LIBS) -o $@
ALL_TARGETS += $(GOAL_BURST)
