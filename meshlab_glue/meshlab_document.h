// MeshLab's document, layer and parameter types for the plugins' host-neutral glue, whichever
// MeshLab it is built against: 2021.05 moved them into folders of their own and made the list of
// layers private (handed out by meshIterator(); 2020.09 keeps pointers in its public meshList).
#ifndef MESHLAB_GLUE_MESHLAB_DOCUMENT_H
#define MESHLAB_GLUE_MESHLAB_DOCUMENT_H

#include <vector>

#if __has_include(<common/ml_document/mesh_document.h>)
#define MESHLAB_GLUE_LAYERS_BY_ITERATOR 1
#include <common/ml_document/mesh_document.h>
#include <common/parameters/rich_parameter_list.h>
#else
#include <common/filter_parameter/rich_parameter_list.h>
#include <common/meshmodel.h>
#endif

namespace meshlab_glue {

/// The document's layers, in its order.
inline std::vector<MeshModel *> Layers(MeshDocument &md)
{
    std::vector<MeshModel *> layers;
#ifdef MESHLAB_GLUE_LAYERS_BY_ITERATOR
    for (MeshModel &layer : md.meshIterator()) layers.push_back(&layer);
#else
    for (MeshModel *layer : md.meshList) layers.push_back(layer);
#endif
    return layers;
}

/// The same, read-only.
inline std::vector<const MeshModel *> Layers(const MeshDocument &md)
{
    std::vector<const MeshModel *> layers;
#ifdef MESHLAB_GLUE_LAYERS_BY_ITERATOR
    for (const MeshModel &layer : md.meshIterator()) layers.push_back(&layer);
#else
    for (const MeshModel *layer : md.meshList) layers.push_back(layer);
#endif
    return layers;
}

} // namespace meshlab_glue

#endif
