#pragma once
// A hand-written COLLADA street for the import and fuzz tests, in the file's own conventions (Z up,
// centimetres): the tetrahedron "Slab" as a <triangles> and a <polylist> half with per-index
// normals and texture coordinates, a textured material and a plain one, and three instances:
// "slab_a" moved 2 m up, "slab_b" turned 90° about z (both under "street", moved 1 m along x),
// and "kerb" from <library_nodes> (a <matrix> moving it 3 m along y) through an <instance_node>.

#include <string>

namespace fissure::test {

inline std::string collada_street() {
  return R"dae(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="centimeter" meter="0.01"/><up_axis>Z_UP</up_axis></asset>
  <library_images><image id="concrete_png"><init_from>concrete.png</init_from></image></library_images>
  <library_effects>
    <effect id="concrete-fx"><profile_COMMON>
      <newparam sid="s"><surface type="2D"><init_from>concrete_png</init_from></surface></newparam>
      <newparam sid="t"><sampler2D><source>s</source></sampler2D></newparam>
      <technique sid="c"><lambert><diffuse><texture texture="t" texcoord="uv"/></diffuse></lambert></technique>
    </profile_COMMON></effect>
    <effect id="glass-fx"><profile_COMMON><technique sid="c"><lambert><diffuse><color>0.2 0.3 0.4 1</color></diffuse></lambert></technique></profile_COMMON></effect>
  </library_effects>
  <library_materials>
    <material id="concrete-mat" name="concrete"><instance_effect url="#concrete-fx"/></material>
    <material id="glass-mat" name="glass"><instance_effect url="#glass-fx"/></material>
  </library_materials>
  <library_geometries>
    <geometry id="Slab" name="Slab"><mesh>
      <source id="Slab-p"><float_array id="Slab-pa" count="12">0 0 0 100 0 0 0 100 0 0 0 100</float_array>
        <technique_common><accessor source="#Slab-pa" count="4" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
      <source id="Slab-n"><float_array id="Slab-na" count="12">0 0 -1 0 -1 0 -1 0 0 0.577 0.577 0.577</float_array>
        <technique_common><accessor source="#Slab-na" count="4" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
      <source id="Slab-uv"><float_array id="Slab-uva" count="8">0 0 1 0 0 1 1 1</float_array>
        <technique_common><accessor source="#Slab-uva" count="4" stride="2"><param name="S" type="float"/><param name="T" type="float"/></accessor></technique_common></source>
      <vertices id="Slab-v"><input semantic="POSITION" source="#Slab-p"/></vertices>
      <triangles material="m" count="2">
        <input semantic="VERTEX" source="#Slab-v" offset="0"/><input semantic="NORMAL" source="#Slab-n" offset="1"/><input semantic="TEXCOORD" source="#Slab-uv" offset="2" set="0"/>
        <p>0 0 0 2 0 2 1 0 1 0 1 0 1 1 1 3 1 3</p></triangles>
      <polylist material="m" count="2">
        <input semantic="VERTEX" source="#Slab-v" offset="0"/><input semantic="NORMAL" source="#Slab-n" offset="1"/><input semantic="TEXCOORD" source="#Slab-uv" offset="2" set="0"/>
        <vcount>3 3</vcount>
        <p>0 2 0 3 2 3 2 2 2 1 3 1 2 3 2 3 3 3</p></polylist>
    </mesh></geometry>
  </library_geometries>
  <library_nodes>
    <node id="kerb" name="kerb"><matrix>1 0 0 0 0 1 0 300 0 0 1 0 0 0 0 1</matrix>
      <instance_geometry url="#Slab"><bind_material><technique_common><instance_material symbol="m" target="#glass-mat"/></technique_common></bind_material></instance_geometry></node>
  </library_nodes>
  <library_visual_scenes><visual_scene id="Scene" name="Scene">
    <node id="street" name="street"><translate>100 0 0</translate>
      <node id="n_slab_a" name="slab_a"><translate>0 0 200</translate>
        <instance_geometry url="#Slab"><bind_material><technique_common><instance_material symbol="m" target="#concrete-mat"/></technique_common></bind_material></instance_geometry></node>
      <node id="slab_b" name="slab_b"><rotate>0 0 1 90</rotate>
        <instance_geometry url="#Slab"><bind_material><technique_common><instance_material symbol="m" target="#glass-mat"/></technique_common></bind_material></instance_geometry></node>
      <node id="kerbs" name="kerbs"><instance_node url="#kerb"/></node>
    </node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#Scene"/></scene>
</COLLADA>
)dae";
}

}  // namespace fissure::test
