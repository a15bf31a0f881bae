# BVH files written at configure time, none checked in (included by tests/CMakeLists.txt, or by
# fuzz/CMakeLists.txt in a tree of the fuzz targets alone):
# - <build>/fuzz-seeds/bvh, the BVH seeds (read beside corpus/<name> where a target has one):
#   - a two-joint clip, and variants of it that each change one thing: its knee's CHANNELS line (a channel
#     repeated, an unknown one, a count far past the names given, too few), the knee named as the root,
#     offsets past a float's range, the frame time (not a number, negative, zero, below a float's range),
#     a frame's values (one too many, too few, nan and inf), no MOTION section, the file cut off mid-joint;
#   - a one-joint clip whose frame count is huge, negative, or past a 64-bit integer;
#   - a chain of 120 joints, one inside the other (the parser's nesting);
#   - a clip with CRLF line ends, tabs and a joint whose channels mix positions and rotations;
#   - the humanoid below.
# - <build>/fuzz-seeds/data, the fixed clips the manifest and retarget targets load: a 22-joint humanoid
#   walking (humanoid.bvh) and a taller one with longer legs (humanoid_tall.bvh).
set(prep_fuzz_seed_dir ${CMAKE_BINARY_DIR}/fuzz-seeds)
string(CONCAT two_joints "HIERARCHY\nROOT hip\n{\n\tOFFSET 0.00 90.0 0.00\n"
                     "\tCHANNELS 6 Xposition Yposition Zposition Yrotation Xrotation Zrotation\n\tJOINT knee\n\t{\n"
                     "\t\tOFFSET 0 -45 0\n\t\tCHANNELS 3 Xrotation Yrotation Zrotation\n\t\tEnd Site\n\t\t{\n"
                     "\t\t\tOFFSET 0 -45 0\n\t\t}\n\t}\n}\nMOTION\nFrames: 3\nFrame Time: 0.008333\n"
                     "0 90 0 0 0 0 0 0 0\n1.5e0 90.25 -2 10 -5.5 3 45 0 -1E1\n3 90.5 -4 20 -11 6 90 0 -20\n")
file(WRITE ${prep_fuzz_seed_dir}/bvh/two_joints.bvh "${two_joints}")
set(knee_channels "CHANNELS 3 Xrotation Yrotation Zrotation")
# name|the text of two_joints.bvh replaced (wherever it occurs)|what replaces it
foreach(variant "channel_repeated|${knee_channels}|CHANNELS 3 Xrotation Xrotation Zrotation"
                "channel_unknown|${knee_channels}|CHANNELS 3 Xrotation Yrotation Wrotation"
                "channels_huge|${knee_channels}|CHANNELS 999999999 Xrotation Yrotation Zrotation"
                "channels_two|${knee_channels}|CHANNELS 2 Xrotation Yrotation"
                "duplicate_names|JOINT knee|JOINT hip"
                "offset_overflow|OFFSET 0 -45 0|OFFSET 0 1e39 0"
                "frame_time_tiny|Frame Time: 0.008333|Frame Time: 1e-300"
                "frame_time_nan|Frame Time: 0.008333|Frame Time: nan"
                "frame_time_negative|Frame Time: 0.008333|Frame Time: -0.01"
                "frame_time_zero|Frame Time: 0.008333|Frame Time: 0"
                "values_extra|3 90.5 -4 20 -11 6 90 0 -20|3 90.5 -4 20 -11 6 90 0 -20 7"
                "values_missing|3 90.5 -4 20 -11 6 90 0 -20|3 90.5 -4 20 -11 6 90"
                "values_nan_inf|1.5e0 90.25 -2 10 -5.5 3 45 0 -1E1|1.5e0 nan -2 inf -5.5 3 45 0 -1E1")
  string(REPLACE "|" ";" parts "${variant}")
  list(GET parts 0 name)
  list(GET parts 1 from)
  list(GET parts 2 to)
  string(FIND "${two_joints}" "${from}" at)
  if(at LESS 0)
    message(FATAL_ERROR "tests/fuzz/bvh_seeds.cmake: two_joints has no '${from}' to make ${name}.bvh from")
  endif()
  string(REPLACE "${from}" "${to}" text "${two_joints}")
  file(WRITE ${prep_fuzz_seed_dir}/bvh/${name}.bvh "${text}")
endforeach()
string(FIND "${two_joints}" "MOTION" at)
string(SUBSTRING "${two_joints}" 0 ${at} text)
file(WRITE ${prep_fuzz_seed_dir}/bvh/no_motion.bvh "${text}")
string(FIND "${two_joints}" "\t\tCHANNELS 3" at)
string(SUBSTRING "${two_joints}" 0 ${at} text)
file(WRITE ${prep_fuzz_seed_dir}/bvh/truncated.bvh "${text}\t\t")

foreach(frames "huge|2147483647" "negative|-5" "overflow|99999999999999999999")
  string(REPLACE "|" ";" parts "${frames}")
  list(GET parts 0 name)
  list(GET parts 1 count)
  file(WRITE ${prep_fuzz_seed_dir}/bvh/frames_${name}.bvh
    "HIERARCHY\nROOT hip\n{\n  OFFSET 0 90 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
    "  End Site\n  {\n    OFFSET 0 10 0\n  }\n}\nMOTION\nFrames: ${count}\nFrame Time: 0.0333333\n0 90 0 0 0 0\n")
endforeach()

set(text "HIERARCHY\nROOT j0\n{\nOFFSET 0 1 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n")
set(closing "}\n")
set(values "0 0 0 0 0 0")
foreach(j RANGE 1 119)
  string(APPEND text "JOINT j${j}\n{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n")
  string(APPEND closing "}\n")
  string(APPEND values " 0 0 0")
endforeach()
string(APPEND text "End Site\n{\nOFFSET 0 1 0\n}\n" "${closing}" "MOTION\nFrames: 1\nFrame Time: 0.0333333\n" "${values}\n")
file(WRITE ${prep_fuzz_seed_dir}/bvh/deep_hierarchy.bvh "${text}")
file(WRITE ${prep_fuzz_seed_dir}/bvh/crlf_tabs_mixed_channels.bvh
  "HIERARCHY\r\nROOT Hips\r\n{\r\n\tOFFSET 0 1 0\r\n\tCHANNELS 3 Zrotation Yrotation Xrotation\r\n\tJOINT Chest\r\n"
  "\t{\r\n\t\tOFFSET 0 0.2 0\r\n\t\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\r\n"
  "\t\tEnd Site\r\n\t\t{\r\n\t\t\tOFFSET 0 0.3 0\r\n\t\t}\r\n\t}\r\n}\r\nMOTION\r\nFrames: 2\r\n"
  "Frame Time: 0.0333333\r\n0 0 0 0 0.2 0 0 0 0\r\n\t1 2 3 0 0.2 0 4 5 6\r\n")

# The humanoid: 22 joints (name|depth|offset|End Site offset, or - for none), CHANNELS as many CMU takes have them. It
# walks one gait cycle of `frames` frames, 4.5 cm forward a frame: at phase p the hips dip 3 sin^2 p cm
# and turn 8 sin p degrees, the arms (held 70 degrees down) swing 15 sin p, the thighs 25 sin p and the
# knees bend 10 +- 10 cos p, the two sides opposite. CMake's arithmetic is integral: sines are a table in
# ten-thousandths (multiples of 6 degrees: 12 or 10 frames a cycle) and the values are kept in hundredths.
set(prep_sine_quadrant 0 1045 2079 3090 4067 5000 5878 6691 7431 8090 8660 9135 9511 9781 9945 10000)
function(prep_sine degrees out)  # sin(degrees) in ten-thousandths, degrees a multiple of 6
  math(EXPR a "((${degrees} % 360) + 360) % 360")
  set(sign 1)
  if(a GREATER_EQUAL 180)
    math(EXPR a "${a} - 180")
    set(sign -1)
  endif()
  if(a GREATER 90)
    math(EXPR a "180 - ${a}")
  endif()
  math(EXPR i "${a} / 6")
  list(GET prep_sine_quadrant ${i} v)
  math(EXPR v "${sign} * ${v}")
  set(${out} ${v} PARENT_SCOPE)
endfunction()
function(prep_hundredths value out)  # an integer in hundredths as a decimal: 9650 -> 96.5, -693 -> -6.93
  set(sign "")
  if(value LESS 0)
    set(sign "-")
    math(EXPR value "-(${value})")
  endif()
  math(EXPR whole "${value} / 100")
  math(EXPR part "${value} % 100")
  if(part EQUAL 0)
    set(text "${whole}")
  elseif(part LESS 10)
    set(text "${whole}.0${part}")
  else()
    string(REGEX REPLACE "0$" "" part "${part}")
    set(text "${whole}.${part}")
  endif()
  if(text STREQUAL "0")
    set(sign "")
  endif()
  set(${out} "${sign}${text}" PARENT_SCOPE)
endfunction()
function(prep_round_div numerator denominator out)  # numerator / denominator to the nearest integer
  if(numerator LESS 0)
    math(EXPR q "-((-(${numerator}) + ${denominator} / 2) / ${denominator})")
  else()
    math(EXPR q "(${numerator} + ${denominator} / 2) / ${denominator}")
  endif()
  set(${out} ${q} PARENT_SCOPE)
endfunction()
function(prep_humanoid file thigh shin hips_height frames)
  set(joints "Hips|0|0 95 0|-" "Spine|1|0 10 0|-" "Spine1|2|0 15 0|-" "Spine2|3|0 15 0|-" "Neck|4|0 12 0|-"
             "Head|5|0 10 0|0 18 0" "LeftShoulder|4|4 10 0|-" "LeftArm|5|14 0 0|-" "LeftForeArm|6|28 0 0|-"
             "LeftHand|7|25 0 0|18 0 0" "RightShoulder|4|-4 10 0|-" "RightArm|5|-14 0 0|-" "RightForeArm|6|-28 0 0|-"
             "RightHand|7|-25 0 0|-18 0 0" "LeftUpLeg|1|10 -5 0|-" "LeftLeg|2|0 -${thigh} 0|-" "LeftFoot|3|0 -${shin} 0|-"
             "LeftToeBase|4|0 -6 13|0 -2 5" "RightUpLeg|1|-10 -5 0|-" "RightLeg|2|0 -${thigh} 0|-"
             "RightFoot|3|0 -${shin} 0|-" "RightToeBase|4|0 -6 13|0 -2 5")
  set(text "HIERARCHY\n")
  set(open 0)  # joints open (their closing braces not yet written)
  foreach(joint ${joints})
    string(REPLACE "|" ";" parts "${joint}")
    list(GET parts 0 name)
    list(GET parts 1 depth)
    list(GET parts 2 offset)
    list(GET parts 3 end_site)
    while(open GREATER depth)
      math(EXPR open "${open} - 1")
      string(REPEAT "  " ${open} pad)
      string(APPEND text "${pad}}\n")
    endwhile()
    string(REPEAT "  " ${depth} pad)
    if(depth EQUAL 0)
      string(APPEND text "ROOT ${name}\n{\n  OFFSET ${offset}\n"
                         "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n")
    else()
      string(APPEND text "${pad}JOINT ${name}\n${pad}{\n${pad}  OFFSET ${offset}\n"
                         "${pad}  CHANNELS 3 Zrotation Xrotation Yrotation\n")
    endif()
    math(EXPR open "${depth} + 1")
    if(NOT end_site STREQUAL "-")
      string(APPEND text "${pad}  End Site\n${pad}  {\n${pad}    OFFSET ${end_site}\n${pad}  }\n")
    endif()
  endforeach()
  while(open GREATER 0)
    math(EXPR open "${open} - 1")
    string(REPEAT "  " ${open} pad)
    string(APPEND text "${pad}}\n")
  endwhile()
  string(APPEND text "MOTION\nFrames: ${frames}\nFrame Time: 0.0333333\n")
  math(EXPR last "${frames} - 1")
  foreach(k RANGE ${last})
    math(EXPR degrees "360 * ${k} / ${frames}")
    prep_sine(${degrees} s)
    math(EXPR cosine_degrees "${degrees} + 90")
    prep_sine(${cosine_degrees} c)
    # hundredths: s and c are in ten-thousandths
    math(EXPR s2 "${s} * ${s}")
    prep_round_div("${s2}" 333333 dip)    # 3 sin^2 p cm = 300 s^2 / 1e8 hundredths
    math(EXPR y "${hips_height} - ${dip}")
    math(EXPR z "450 * ${k}")
    math(EXPR yaw_num "2 * ${s}")
    prep_round_div("${yaw_num}" 25 yaw)  # 8 sin p = 800 s / 1e4 hundredths
    math(EXPR arm_num "15 * ${s}")
    prep_round_div("${arm_num}" 100 arm)  # 15 sin p
    math(EXPR leg_num "25 * ${s}")
    prep_round_div("${leg_num}" 100 thigh_swing)  # 25 sin p
    prep_round_div("${c}" 10 knee_swing)  # 10 cos p
    math(EXPR left_knee "1000 + ${knee_swing}")
    math(EXPR right_knee "1000 - ${knee_swing}")
    math(EXPR minus_arm "-(${arm})")
    math(EXPR minus_thigh "-(${thigh_swing})")
    set(values)
    foreach(h 0 ${y} ${z} 0 0 ${yaw})  # the root: position, then Z X Y rotations
      prep_hundredths(${h} v)
      list(APPEND values ${v})
    endforeach()
    # 21 joints of three rotations each, Z X Y, in the order above; zero but for the arms, thighs and knees
    set(rotations)
    foreach(i RANGE 62)
      list(APPEND rotations 0)
    endforeach()
    foreach(entry "18|-7000" "19|${arm}" "30|7000" "31|${minus_arm}" "40|${minus_thigh}" "43|${left_knee}"
                  "52|${thigh_swing}" "55|${right_knee}")
      string(REPLACE "|" ";" parts "${entry}")
      list(GET parts 0 i)
      list(GET parts 1 h)
      prep_hundredths(${h} v)
      list(REMOVE_AT rotations ${i})
      list(INSERT rotations ${i} ${v})
    endforeach()
    list(APPEND values ${rotations})
    list(JOIN values " " row)
    string(APPEND text "${row}\n")
  endforeach()
  file(WRITE ${file} "${text}")
endfunction()
prep_humanoid(${prep_fuzz_seed_dir}/data/humanoid.bvh 42 40 9650 12)
prep_humanoid(${prep_fuzz_seed_dir}/data/humanoid_tall.bvh 48.3 46 10850 10)
file(COPY ${prep_fuzz_seed_dir}/data/humanoid.bvh DESTINATION ${prep_fuzz_seed_dir}/bvh)
