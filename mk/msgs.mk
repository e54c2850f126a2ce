# LCM types (msgs/*.lcm, package hylo) -> C, C++ and Python bindings under
# build/gen/lcm/. Generated code is never committed.
#   c/           C with publish/subscribe (links liblcm; for the LCM node)
#   c-nopubsub/  C encode/decode only (no liblcm; for the core's tests)
#   cpp/ python/
LCM_GEN ?= /usr/bin/lcm-gen
MSG_FILES := $(wildcard msgs/*.lcm)
MSG_NAMES := $(basename $(notdir $(MSG_FILES)))
LCM_GEN_DIR := $(BUILD)/gen/lcm
LCM_STAMP := $(LCM_GEN_DIR)/.stamp
MSG_C_SRCS := $(MSG_NAMES:%=$(LCM_GEN_DIR)/c/hylo_%.c)
MSG_NOPUBSUB_SRCS := $(MSG_NAMES:%=$(LCM_GEN_DIR)/c-nopubsub/hylo_%.c)
# lcm-gen's C does not pass -pedantic -Wextra (docs/deps.md).
LCM_GEN_REQUIRED := -std=c99 -ffp-contract=off -Wall -Werror -Wno-pedantic -Wno-format -Wno-unused-parameter
LCM_GEN_CFLAGS := $(LCM_GEN_REQUIRED) $(LCM_CFLAGS) $(CPPFLAGS) $(CFLAGS)

$(LCM_STAMP): $(MSG_FILES)
	@rm -rf $(LCM_GEN_DIR) && mkdir -p $(LCM_GEN_DIR)/c $(LCM_GEN_DIR)/c-nopubsub $(LCM_GEN_DIR)/cpp $(LCM_GEN_DIR)/python
	$(LCM_GEN) -c --c-cpath $(LCM_GEN_DIR)/c --c-hpath $(LCM_GEN_DIR)/c $(MSG_FILES)
	$(LCM_GEN) -c --c-no-pubsub --c-cpath $(LCM_GEN_DIR)/c-nopubsub --c-hpath $(LCM_GEN_DIR)/c-nopubsub $(MSG_FILES)
	$(LCM_GEN) -x --cpp-std c++11 --cpp-hpath $(LCM_GEN_DIR)/cpp $(MSG_FILES)
	$(LCM_GEN) -p --ppath $(LCM_GEN_DIR)/python $(MSG_FILES)
	@touch $@

$(MSG_C_SRCS) $(MSG_NOPUBSUB_SRCS): $(LCM_STAMP) ;

$(BUILD)/obj/gen/%.o: $(BUILD)/gen/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(LCM_GEN_CFLAGS) $(DEP_FLAGS) -c $< -o $@

# LCM 1.3.1's array coders call memcpy(NULL, src, 0) for empty arrays (its
# lcm_coretypes.h): harmless, but UBSan's nonnull check would stop every test
# that decodes an empty array. Only the generated code is exempted.
$(BUILD)/san/obj/gen/%.o: $(BUILD)/gen/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CC) $(LCM_GEN_CFLAGS) $(SAN_FLAGS) -fno-sanitize=nonnull-attribute $(DEP_FLAGS) -c $< -o $@

MSG_NOPUBSUB_OBJS := $(MSG_NAMES:%=$(BUILD)/obj/gen/lcm/c-nopubsub/hylo_%.o)
MSG_NOPUBSUB_OBJS_SAN := $(MSG_NAMES:%=$(BUILD)/san/obj/gen/lcm/c-nopubsub/hylo_%.o)
MSG_OBJS := $(MSG_NAMES:%=$(BUILD)/obj/gen/lcm/c/hylo_%.o)

ALL_TARGETS += $(LCM_STAMP) $(MSG_NOPUBSUB_OBJS) $(MSG_OBJS)
