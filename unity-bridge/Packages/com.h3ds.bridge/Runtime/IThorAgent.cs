// How the package reaches AI2-THOR. AI2-THOR's scripts live in its Unity project's Assembly-CSharp,
// which a package cannot reference; the project implements this interface in one small script
// (Samples~/ThorAdapter/ThorAgentAdapter.cs, copied into its Assets) and the bridge calls it.
using System.Collections;
using System.Collections.Generic;
using UnityEngine;

namespace H3ds.Bridge
{
    /// <summary>The outcome of one AI2-THOR action.</summary>
    public sealed class ThorResult
    {
        public bool Done, Success;
        public string Error;
    }

    /// <summary>An object AI2-THOR spawned from the house JSON: its house id, type and GameObject.</summary>
    public struct SpawnedObject
    {
        public string ObjectId, ObjectType;
        public GameObject GameObject;
    }

    public interface IThorAgent
    {
        /// <summary>Runs one action dict exactly as controller.step(**action) takes it ("action", "objectId",
        /// "forceAction", "house"...), over as many frames as AI2-THOR needs; fills result when done.</summary>
        IEnumerator Run(Dictionary<string, object> action, ThorResult result);

        /// <summary>The objects of the current house, after CreateHouse.</summary>
        IEnumerable<SpawnedObject> SpawnedObjects();
    }
}
